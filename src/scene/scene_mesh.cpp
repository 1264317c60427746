// A garment's or obstacle's `mesh` (docs/scene-format.md, "garments[i]" and "obstacles[i]"): an
// OBJ file, a grid, a dress or tube pattern (garments) or a sphere (obstacles).
#include "scene/scene_blocks.hpp"

#include "core/mesh_build.hpp"
#include "io/obj.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

double parse_cell(const JsonValue& d, double fallback) {
  const double cell = d.positive_or("cell", fallback);
  if (cell < 0.002 || cell > 0.5) d.at("cell").fail("must be between 0.002 and 0.5 m");
  return cell;
}

int parse_around(const JsonValue& d, int fallback) {
  const long long around = d.integer_or("around", fallback);
  if (around < 16 || around > 1000 || around % 8 != 0) d.at("around").fail("must be a multiple of 8 between 16 and 1000");
  return static_cast<int>(around);
}

DressParams parse_dress(const JsonValue& d) {
  d.only_keys({"around", "cell", "bodice_radius", "top_height", "hem_height", "hem_radius"});
  DressParams p;
  p.around = parse_around(d, p.around);
  p.cell = parse_cell(d, p.cell);
  p.bodice_radius = d.positive_or("bodice_radius", p.bodice_radius);
  p.top_height = d.positive_or("top_height", p.top_height);
  p.hem_height = d.positive_or("hem_height", p.hem_height);
  p.hem_radius = d.positive_or("hem_radius", p.hem_radius);
  if (p.bodice_radius < 0.16 || p.bodice_radius > 0.3) d.at("bodice_radius").fail("must be between 0.16 and 0.3 m (the figure's chest)");
  if (p.top_height < p.waist_height + 0.1 || p.top_height > 1.4) d.at("top_height").fail("must be between 1.15 and 1.4 m (waist to armpits)");
  if (p.hem_height >= p.waist_height) d.at("hem_height").fail("must be below the waist (1.05 m)");
  if (p.hem_radius <= p.bodice_radius) d.at("hem_radius").fail("must be more than the bodice radius");
  return p;
}

TubeParams parse_tube(const JsonValue& t) {
  t.only_keys({"around", "cell", "top", "bottom"});
  TubeParams p;
  p.around = parse_around(t, p.around);
  p.cell = parse_cell(t, p.cell);
  const Vec2 top = t.at("top").vec2(), bottom = t.at("bottom").vec2();
  if (!(top.y() > 0)) t.at("top").fail("expected [height, radius] with a radius greater than 0");
  if (!(bottom.y() > 0)) t.at("bottom").fail("expected [height, radius] with a radius greater than 0");
  if (!(bottom.x() < top.x())) t.at("bottom").fail("the bottom ring must be below the top ring");
  p.top_height = top.x();
  p.top_radius = top.y();
  p.bottom_height = bottom.x();
  p.bottom_radius = bottom.y();
  return p;
}

Mesh parse_sphere(const JsonValue& sp) {
  sp.only_keys({"radius", "subdivisions"});
  long long sub = sp.integer_or("subdivisions", 3);
  if (sub < 0 || sub > 6) sp.at("subdivisions").fail("must be between 0 and 6");
  return build_mesh(make_icosphere(sp.at("radius").positive(), static_cast<int>(sub)));
}

Mesh parse_grid(const JsonValue& g) {
  g.only_keys({"size", "cells"});
  Vec2 size = g.at("size").vec2();
  if (!(size.x() > 0 && size.y() > 0)) g.at("size").fail("sizes must be greater than 0");
  JsonValue cells = g.at("cells");
  auto c = cells.items();
  if (c.size() != 2) cells.fail("expected [nx, ny]");
  long long nx = c[0].integer(), ny = c[1].integer();
  if (nx < 1 || ny < 1 || nx > 1'000'000 || ny > 1'000'000 || nx * ny > 1'000'000)
    cells.fail("cell counts must be between 1 and 1,000,000 in all (2,000,000 triangles)");
  return build_mesh(make_grid(size.x(), size.y(), static_cast<int>(nx), static_cast<int>(ny)));
}

}  // namespace

ObstacleSurface obstacle_surface(const MeshSource& surface, const std::string& file, std::vector<std::string>* notes) {
  ObstacleSurface built = [&] {
    try {
      return build_obstacle_mesh(surface);
    } catch (const MeshBuildError& e) {
      throw InputError(file, "", std::string("cannot be a collision surface: ") + e.what());
    }
  }();
  if (const std::string found = built.repairs.summary(); notes && !found.empty()) notes->push_back(file + ": " + found);
  return built;
}

Mesh parse_mesh(const JsonValue& j, const std::string& scene_path, bool garment, std::optional<GarmentPattern>* pattern,
                std::vector<std::string>* notes) {
  if (j.is_string()) {
    std::string file = resolve_file(j, scene_path);
    if (garment) return with_key(j, [&] { return read_obj(file, true); });
    return with_key(j, [&] { return obstacle_surface(read_obj_source(file, false), file, notes).mesh; });
  }
  j.only_keys({"grid", "sphere", "dress", "tube"});
  auto garment_only = [&](const JsonValue& d, const char* what) {
    if (!garment) d.fail(std::string("an obstacle cannot be a ") + what);
  };
  if (auto d = j.find("dress")) {
    garment_only(*d, "dress");
    const DressParams p = parse_dress(*d);
    if (pattern) *pattern = p;
    return build_mesh(make_dress(p));
  }
  if (auto t = j.find("tube")) {
    garment_only(*t, "tube");
    const TubeParams p = parse_tube(*t);
    if (pattern) *pattern = p;
    return build_mesh(make_tube(p));
  }
  if (auto sp = j.find("sphere")) {
    if (garment) sp->fail("a garment cannot be a sphere (it needs a pattern)");
    return parse_sphere(*sp);
  }
  return parse_grid(j.at("grid"));
}

}  // namespace vdc
