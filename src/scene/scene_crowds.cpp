// The `crowds` block (docs/scene-format.md, "crowds[i]"): copies of a template character and its
// garments, placed and varied from a seed.
#include "scene/scene_crowds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vdc {

namespace {

// splitmix64 (Steele, Lea and Flood 2014): the same draws on every platform and compiler, which
// the standard library's distributions do not promise.
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : state_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(uniform(0, static_cast<double>(n))) % n; }

 private:
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

// A crowd key given as a number or as a range [lo, hi] drawn from uniformly (a draw only for a
// range); `fallback` when absent.
struct Spread {
  double lo, hi;
  double draw(Draws& draws) const { return lo == hi ? lo : draws.uniform(lo, hi); }
};
Spread spread_or(const JsonValue& crowd, const char* key, double fallback, bool positive) {
  const auto v = crowd.find(key);
  if (!v) return {fallback, fallback};
  auto check = [&](const JsonValue& x) { return positive ? x.positive() : x.number(); };
  if (!v->is_array()) {
    const double x = check(*v);
    return {x, x};
  }
  const auto range = v->items();
  if (range.size() != 2) v->fail("expected a number or a range [lo, hi]");
  const Spread s{check(range[0]), check(range[1])};
  if (s.hi < s.lo) v->fail("the range's end is below its start");
  return s;
}

std::vector<Vec3> layout_positions(const JsonValue& crowd, int count, const Vec3& centre, Draws& draws) {
  const JsonValue layout = crowd.at("layout");
  layout.only_keys({"grid", "circle", "random"});
  if (layout.raw().size() != 1) layout.fail("expected one of grid, circle or random");
  std::vector<Vec3> at;
  if (const auto grid = layout.find("grid")) {
    grid->only_keys({"columns", "spacing"});
    const long long columns = grid->integer_or("columns", static_cast<long long>(std::ceil(std::sqrt(static_cast<double>(count)) - 1e-9)));
    if (columns < 1 || columns > count) grid->at("columns").fail("must be between 1 and the crowd's count");
    Vec2 spacing(2, 2);
    if (const auto s = grid->find("spacing")) spacing = s->is_array() ? s->vec2() : Vec2(s->positive(), s->positive());
    if (!(spacing.x() > 0 && spacing.y() > 0)) grid->at("spacing").fail("must be greater than 0");
    const long long rows = (count + columns - 1) / columns;
    for (int k = 0; k < count; ++k) {
      const double column = static_cast<double>(k % columns), row = static_cast<double>(k / columns);
      at.push_back(centre + Vec3((column - 0.5 * static_cast<double>(columns - 1)) * spacing.x(), 0,
                                 (row - 0.5 * static_cast<double>(rows - 1)) * spacing.y()));
    }
  } else if (const auto circle = layout.find("circle")) {
    circle->only_keys({"radius"});
    const double radius = circle->at("radius").positive();
    for (int k = 0; k < count; ++k) {
      const double angle = 2 * M_PI * k / count;
      at.push_back(centre + Vec3(radius * std::sin(angle), 0, radius * std::cos(angle)));
    }
  } else {
    const JsonValue random = layout.at("random");
    random.only_keys({"size", "min_distance"});
    const Vec2 size = random.at("size").vec2();
    if (!(size.x() > 0 && size.y() > 0)) random.at("size").fail("sizes must be greater than 0");
    const double apart = random.non_negative_or("min_distance", 1.0);
    constexpr int kTries = 1000;
    for (int k = 0; k < count; ++k) {
      bool placed = false;
      for (int t = 0; t < kTries && !placed; ++t) {
        const Vec3 p = centre + Vec3(draws.uniform(-0.5 * size.x(), 0.5 * size.x()), 0, draws.uniform(-0.5 * size.y(), 0.5 * size.y()));
        placed = std::none_of(at.begin(), at.end(), [&](const Vec3& q) { return (p - q).norm() < apart; });
        if (placed) at.push_back(p);
      }
      if (!placed)
        random.fail("could not place copy " + std::to_string(k + 1) + " of " + std::to_string(count) + " at least " + std::to_string(apart) +
                    " m from the others in " + std::to_string(kTries) + " tries: enlarge the size or lower min_distance");
    }
  }
  return at;
}

std::string numbered(const std::string& name, int k, int count) {
  std::string digits = std::to_string(k);
  const std::size_t width = std::max<std::size_t>(2, std::to_string(count).size());
  return name + std::string(width - std::min(width, digits.size()), '0') + digits;
}

}  // namespace

std::vector<CrowdCopy> place_crowd(const JsonValue& crowd) {
  crowd.only_keys({"name", "count", "layout", "centre", "heading", "start", "speed", "motions", "motion_order", "mirror", "seed", "template"});
  const std::string name = crowd.at("name").string();
  const long long count = crowd.at("count").integer();
  if (count < 1 || count > 10000) crowd.at("count").fail("must be between 1 and 10,000");
  const long long seed = crowd.integer_or("seed", 1);
  Draws draws(static_cast<std::uint64_t>(seed));
  const Vec3 centre = crowd.vec3_or("centre", Vec3::Zero());
  const std::vector<Vec3> positions = layout_positions(crowd, static_cast<int>(count), centre, draws);
  const auto heading_key = crowd.find("heading");
  const bool face_centre = heading_key && heading_key->is_string();
  if (face_centre && heading_key->string() != "centre") heading_key->fail("expected degrees, a range [lo, hi] or \"centre\"");
  const Spread heading = face_centre ? Spread{0, 0} : spread_or(crowd, "heading", 0, false);
  const Spread start = spread_or(crowd, "start", 0, false), speed = spread_or(crowd, "speed", 1, true);
  std::vector<std::string> motions;
  if (const auto m = crowd.find("motions")) {
    for (const JsonValue& file : m->items()) motions.push_back(file.string());
    if (motions.empty()) m->fail("expected at least one motion file");
  }
  const std::string order = crowd.string_or("motion_order", "cycle");
  if (order != "cycle" && order != "random") crowd.at("motion_order").fail("expected \"cycle\" or \"random\"");
  std::string mirror = "none";
  if (const auto m = crowd.find("mirror")) {
    const bool word = m->is_string() && (m->string() == "alternate" || m->string() == "random");
    if (!word && !m->raw().is_boolean()) m->fail("expected true, false, \"alternate\" or \"random\"");
    mirror = word ? m->string() : m->boolean() ? "all" : "none";
  }
  std::vector<CrowdCopy> copies;
  for (int k = 0; k < count; ++k) {
    CrowdCopy c;
    c.group = numbered(name, k + 1, static_cast<int>(count));
    c.position = positions[static_cast<std::size_t>(k)];
    const Vec3 to_centre = centre - c.position;
    c.heading = face_centre ? (to_centre.norm() > 1e-9 ? std::atan2(to_centre.x(), to_centre.z()) * 180 / M_PI : 0.0) : heading.draw(draws);
    c.start = start.draw(draws);
    c.speed = speed.draw(draws);
    if (!motions.empty()) c.motion = motions[order == "cycle" ? static_cast<std::size_t>(k) % motions.size() : draws.below(motions.size())];
    c.mirror = mirror == "all" || (mirror == "alternate" && k % 2 == 1) || (mirror == "random" && draws.below(2) == 1);
    copies.push_back(c);
  }
  return copies;
}

SceneEntries scene_entries(const JsonValue& scene) {
  SceneEntries entries;
  if (const auto g = scene.find("garments")) entries.garments = g->items();
  if (const auto o = scene.find("obstacles")) entries.obstacles = o->items();
  const auto crowds = scene.find("crowds");
  if (!crowds) return entries;
  for (const JsonValue& crowd : crowds->items()) {
    const std::vector<CrowdCopy> copies = place_crowd(crowd);
    const JsonValue made = crowd.at("template");
    made.only_keys({"character", "garments"});
    const JsonValue character = made.at("character");
    character.expect_object();
    const double start = character.number_or("start", 0.0), speed = character.positive_or("speed", 1.0);
    const auto garments = made.at("garments").items();
    if (garments.empty()) made.at("garments").fail("a crowd's template needs at least one garment");
    for (const JsonValue& g : garments) {
      g.expect_object();
      g.at("name").string();
      for (const char* key : {"group", "transform"})
        if (g.has(key)) g.at(key).fail("a crowd's copies take their group and their place from the crowd");
    }
    for (const CrowdCopy& c : copies) {
      const nlohmann::json place = {{"rotate", {0.0, c.heading, 0.0}}, {"translate", {c.position.x(), c.position.y(), c.position.z()}}};
      for (std::size_t gi = 0; gi < garments.size(); ++gi) {
        nlohmann::json g = garments[gi].raw();
        g["name"] = g["name"].get<std::string>() + "_" + c.group;
        g["group"] = c.group;
        g["transform"] = place;
        entries.garments.emplace_back(std::move(g), crowd.file(), garments[gi].path() + "[" + c.group + "]");
      }
      nlohmann::json figure = character.raw();
      figure["start"] = start + c.start;
      figure["speed"] = speed * c.speed;
      if (!c.motion.empty()) figure["motion"] = c.motion;
      if (c.mirror) figure["mirror"] = true;
      entries.obstacles.emplace_back(nlohmann::json{{"name", c.group}, {"group", c.group}, {"character", std::move(figure)}, {"transform", place}},
                                     crowd.file(), made.path() + "[" + c.group + "]");
    }
  }
  return entries;
}

}  // namespace vdc
