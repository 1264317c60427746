#include "scene/scene.hpp"

#include "scene/joint_names.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <optional>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <variant>

#include "core/bvh.hpp"
#include "core/mesh_build.hpp"
#include "core/track.hpp"
#include "io/json_reader.hpp"
#include "io/obj.hpp"
#include "physics/cloth_model.hpp"
#include "scene/body.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/crowd.hpp"
#include "scene/dressing.hpp"
#include "scene/figure.hpp"
#include "scene/fitting.hpp"
#include "scene/garments.hpp"
#include "scene/joint_names.hpp"
#include "scene/material_file.hpp"
#include "scene/obj_sequence.hpp"
#include "scene/transform.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

std::string resolve(const JsonValue& j, const std::string& scene_path) {
  std::string rel = j.string();
  if (rel.empty()) j.fail("empty file name");
  fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(scene_path).parent_path() / rel;
  std::error_code ec;
  const fs::file_status status = fs::status(p, ec);
  if (!fs::exists(status)) {
    // A name the system cannot look up (too long, a loop of links) is named with the reason.
    const bool absent = !ec || ec == std::errc::no_such_file_or_directory || ec == std::errc::not_a_directory;
    j.fail((absent ? std::string("file not found") : "cannot look up the file (" + ec.message() + ")") + ": " + shortened(p.string()));
  }
  if (!fs::is_regular_file(status)) j.fail("not a regular file: " + shortened(p.string()));
  return p.string();
}

// A character's skeleton must be of a person's size once scaled: a capture in other units (CMU's
// captures in inches, others in centimetres) would otherwise make a figure metres or millimetres
// tall, and the garments around it meaningless. The size is the largest extent of its joints in
// the rest pose; `place` is what the error names (the scale, or the motion without one).
void check_figure_size(const Motion& motion, double scale, const JsonValue& place) {
  constexpr double kShortest = 0.5, kTallest = 3.0, kTypical = 1.7;  // m
  Aabb box;
  for (const auto& joint : motion.world(Body::rest_pose(motion.skeleton))) box.grow(Vec3(joint.translation()));
  const double size = (box.hi - box.lo).maxCoeff();
  if (size >= kShortest && size <= kTallest) return;
  std::ostringstream problem;
  problem << "the figure is " << std::setprecision(3) << size << " m tall with scale " << scale
          << " (its skeleton's extent in the rest pose), not 0.5 to 3 m";
  if (size > 0) problem << ": scale " << std::setprecision(3) << scale * kTypical / size << " would make it 1.7 m";
  place.fail(problem.str());
}

// How far a capture's root stands, across the floor, from the origin at a frame: the
// shift that brings the figure to where the scene's transform places it (its height kept).
Vec3 recentering(const Motion& motion, int frame) {
  const Vec3 root = motion.world(motion.frame_pose(static_cast<std::size_t>(frame))).front().translation();
  return Vec3(root.x(), 0.0, root.z());
}

// A capture whose first pose is further than this from the dressing pose (m, any joint) gets
// kDefaultPreroll seconds of pre-roll unless its scene says otherwise.
constexpr double kStillDistance = 0.01, kDefaultPreroll = 1.0, kLongestPreroll = 60.0;
// What a character's arms keep from its body by default and from what its garments' handles
// hold (m; build_clearing_arms, GarmentFit::ease_clearing_arms), and how far apart in time the
// poses they are checked in are (s).
constexpr double kArmClearance = 0.01, kPoseSampleTime = 1.0 / 30;

// Runs a loader of a referenced file; its errors keep their own file and line and gain the key path.
template <class F>
auto with_key(const JsonValue& j, F&& load) {
  try {
    return load();
  } catch (const InputError& e) {
    throw InputError(j.file(), j.path(), e.what());
  }
}

// Keyframes [{"time": t, "<name>": [x, y, z]}, ...] with increasing times.
Vec3Track parse_track(const JsonValue& list, const char* name) {
  Vec3Track track;
  for (const JsonValue& k : list.items()) {
    k.only_keys({"time", name});
    Vec3Key key{k.at("time").non_negative(), k.at(name).vec3()};
    if (!track.keys.empty() && !(key.time > track.keys.back().time)) k.at("time").fail("keyframe times must increase");
    track.keys.push_back(key);
  }
  return track;
}

Transform parse_transform(const JsonValue& j) {
  j.only_keys({"scale", "rotate", "translate"});
  Transform t;
  t.scale = j.positive_or("scale", 1.0);
  t.rotate_degrees = j.vec3_or("rotate", Vec3::Zero());
  t.translate = j.vec3_or("translate", Vec3::Zero());
  return t;
}

// With `pattern`, a procedural garment's sizes are kept there.
Mesh parse_mesh(const JsonValue& j, const std::string& scene_path, bool garment, std::optional<GarmentPattern>* pattern = nullptr) {
  if (j.is_string()) {
    std::string file = resolve(j, scene_path);
    return with_key(j, [&] { return read_obj(file, garment); });
  }
  j.only_keys({"grid", "sphere", "dress", "tube"});
  auto garment_only = [&](const JsonValue& d, const char* what) {
    if (!garment) d.fail(std::string("an obstacle cannot be a ") + what);
  };
  auto parse_cell = [](const JsonValue& d, double fallback) {
    const double cell = d.positive_or("cell", fallback);
    if (cell < 0.002 || cell > 0.5) d.at("cell").fail("must be between 0.002 and 0.5 m");
    return cell;
  };
  auto parse_around = [](const JsonValue& d, int fallback) {
    const long long around = d.integer_or("around", fallback);
    if (around < 16 || around > 1000 || around % 8 != 0) d.at("around").fail("must be a multiple of 8 between 16 and 1000");
    return static_cast<int>(around);
  };
  if (auto d = j.find("dress")) {
    garment_only(*d, "dress");
    d->only_keys({"around", "cell", "bodice_radius", "top_height", "hem_height", "hem_radius"});
    DressParams p;
    p.around = parse_around(*d, p.around);
    p.cell = parse_cell(*d, p.cell);
    p.bodice_radius = d->positive_or("bodice_radius", p.bodice_radius);
    p.top_height = d->positive_or("top_height", p.top_height);
    p.hem_height = d->positive_or("hem_height", p.hem_height);
    p.hem_radius = d->positive_or("hem_radius", p.hem_radius);
    if (p.bodice_radius < 0.16 || p.bodice_radius > 0.3) d->at("bodice_radius").fail("must be between 0.16 and 0.3 m (the figure's chest)");
    if (p.top_height < p.waist_height + 0.1 || p.top_height > 1.4) d->at("top_height").fail("must be between 1.15 and 1.4 m (waist to armpits)");
    if (p.hem_height >= p.waist_height) d->at("hem_height").fail("must be below the waist (1.05 m)");
    if (p.hem_radius <= p.bodice_radius) d->at("hem_radius").fail("must be more than the bodice radius");
    if (pattern) *pattern = p;
    return build_mesh(make_dress(p));
  }
  if (auto t = j.find("tube")) {
    garment_only(*t, "tube");
    t->only_keys({"around", "cell", "top", "bottom"});
    TubeParams p;
    p.around = parse_around(*t, p.around);
    p.cell = parse_cell(*t, p.cell);
    const Vec2 top = t->at("top").vec2(), bottom = t->at("bottom").vec2();
    if (!(top.y() > 0)) t->at("top").fail("expected [height, radius] with a radius greater than 0");
    if (!(bottom.y() > 0)) t->at("bottom").fail("expected [height, radius] with a radius greater than 0");
    if (!(bottom.x() < top.x())) t->at("bottom").fail("the bottom ring must be below the top ring");
    p.top_height = top.x();
    p.top_radius = top.y();
    p.bottom_height = bottom.x();
    p.bottom_radius = bottom.y();
    if (pattern) *pattern = p;
    return build_mesh(make_tube(p));
  }
  if (auto sp = j.find("sphere")) {
    if (garment) sp->fail("a garment cannot be a sphere (it needs a pattern)");
    sp->only_keys({"radius", "subdivisions"});
    long long sub = sp->integer_or("subdivisions", 3);
    if (sub < 0 || sub > 6) sp->at("subdivisions").fail("must be between 0 and 6");
    return build_mesh(make_icosphere(sp->at("radius").positive(), static_cast<int>(sub)));
  }
  JsonValue g = j.at("grid");
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

Material parse_material_ref(const JsonValue& j, const std::string& scene_path) {
  if (j.is_string()) {
    std::string file = resolve(j, scene_path);
    return with_key(j, [&] { return load_material(file); });
  }
  return parse_material(j);
}

NodeId nearest_node(const Mesh& mesh, const Vec3& p) {
  NodeId best;
  double d = std::numeric_limits<double>::infinity();
  for (NodeId n : mesh.nodes())
    if (double e = (mesh.x(n) - p).squaredNorm(); e < d) d = e, best = n;
  return best;
}

NodeId nearest_vert_node(const Mesh& mesh, const Vec2& u) {
  VertId best;
  double d = std::numeric_limits<double>::infinity();
  for (VertId v : mesh.verts())
    if (double e = (mesh.u(v) - u).squaredNorm(); e < d) d = e, best = v;
  return mesh.vert_node(best);
}

// Node n of a garment's mesh held by handle `index`, anchored where it is.
void hold_node(Mesh& mesh, NodeId n, int32_t index) {
  mesh.node_attrs().get<int32_t>(kHandleAttr)[n] = index;
  mesh.node_attrs().get<Vec3>(kAnchorAttr)[n] = mesh.x(n);
  mesh.flags(n) |= kNodeHandle;
}

void parse_handles(const JsonValue& list, GarmentSpec& g) {
  const auto& which = g.mesh.node_attrs().get<int32_t>(kHandleAttr);
  for (const JsonValue& h : list.items()) {
    h.only_keys({"nodes", "points", "uv", "box", "release", "path", "attach"});
    ClothHandle handle;
    handle.release = h.has("release") ? h.at("release").non_negative() : std::numeric_limits<double>::infinity();
    if (auto path = h.find("path")) handle.path = parse_track(*path, "offset");
    std::vector<NodeId> nodes;
    if (auto ids = h.find("nodes"))
      for (const JsonValue& id : ids->items()) {
        long long i = id.integer();
        if (i < 0 || i >= g.mesh.num_nodes())
          id.fail("node index out of range (the mesh has " + std::to_string(g.mesh.num_nodes()) + " nodes)");
        nodes.push_back(NodeId(static_cast<int32_t>(i)));
      }
    if (auto pts = h.find("points"))
      for (const JsonValue& p : pts->items()) nodes.push_back(nearest_node(g.mesh, p.vec3()));
    if (auto uvs = h.find("uv"))
      for (const JsonValue& u : uvs->items()) nodes.push_back(nearest_vert_node(g.mesh, u.vec2()));
    if (auto box = h.find("box")) {
      const auto corners = box->items();
      if (corners.size() != 2) box->fail("expected [[x0, y0, z0], [x1, y1, z1]]");
      const Vec3 lo = corners[0].vec3(), hi = corners[1].vec3();
      if (!(lo.array() <= hi.array()).all()) box->fail("the first corner must be the lower one on every axis");
      std::size_t before = nodes.size();
      for (NodeId n : g.mesh.nodes())
        if ((g.mesh.x(n).array() >= lo.array()).all() && (g.mesh.x(n).array() <= hi.array()).all()) nodes.push_back(n);
      if (nodes.size() == before) box->fail("no node of the garment is in the box");
    }
    if (nodes.empty()) h.fail("a handle needs at least one of nodes, points, uv or box");
    const auto index = static_cast<int32_t>(g.handles.size());
    for (NodeId n : nodes) {
      if (which[n] >= 0 && which[n] != index) h.fail("node " + std::to_string(n.idx) + " already belongs to another handle");
      hold_node(g.mesh, n, index);
    }
    g.handles.push_back(handle);
  }
}

// What making a garment again for the figure wearing it needs (fit_garment).
struct GarmentMaking {
  std::optional<GarmentPattern> pattern;  // a procedural garment's sizes on the project's figure, to make it again for another
  std::optional<Transform> transform;
  bool rest_initial = false;
};

// The garment placed in the world as given, on the project's figure; handles chosen on it.
GarmentSpec parse_garment(const JsonValue& j, const std::string& scene_path, GarmentMaking& making) {
  j.only_keys({"name", "group", "mesh", "material", "transform", "handles", "rest_shape", "fit", "sheer"});
  GarmentSpec g;
  g.name = j.at("name").string();
  g.group = j.string_or("group", "");
  g.sheer = j.boolean_or("sheer", false);
  g.mesh = parse_mesh(j.at("mesh"), scene_path, true, &making.pattern);
  g.material = parse_material_ref(j.at("material"), scene_path);
  if (auto t = j.find("transform")) {
    making.transform = parse_transform(*t);
    for (NodeId n : g.mesh.nodes()) g.mesh.x(n) = making.transform->apply(g.mesh.x(n));
  }
  std::string rest = j.string_or("rest_shape", "flat");
  making.rest_initial = rest == "initial";
  if (making.rest_initial) set_rest_angles_from_world(g.mesh);
  else if (rest != "flat") j.at("rest_shape").fail("expected \"flat\" or \"initial\"");
  g.mesh.node_attrs().add<int32_t>(kHandleAttr, -1);
  g.mesh.node_attrs().add<Vec3>(kAnchorAttr, Vec3::Zero());
  if (auto h = j.find("handles")) parse_handles(*h, g);
  return g;
}

// The character a garment is fitted to: its "fit" (a character's name, or false for none), by
// default the one character among the obstacles it collides with (its group's and those of no
// group), if there is exactly one. Null: the garment is made as given.
const ObstacleSpec* garment_wearer(const JsonValue& j, const GarmentSpec& g, const GarmentMaking& making, const std::vector<ObstacleSpec>& obstacles) {
  const auto fit = j.find("fit");
  if (fit && fit->raw().is_boolean() && !fit->boolean()) return nullptr;
  if (fit && fit->is_string()) {
    const std::string name = fit->string();
    const auto o = std::find_if(obstacles.begin(), obstacles.end(), [&](const ObstacleSpec& x) { return x.name == name; });
    if (o == obstacles.end()) fit->fail("no obstacle named '" + name + "'");
    if (!o->character) fit->fail("'" + name + "' is not a character");
    if (!o->group.empty() && o->group != g.group) fit->fail("'" + name + "' is in another group than the garment");
    if (!making.pattern) fit->fail("only a procedural garment (dress or tube) can be fitted to a character");
    return &*o;
  }
  if (fit && !fit->raw().is_boolean()) fit->fail("expected a character's name, true (the default) or false");
  if (!making.pattern) return nullptr;
  const ObstacleSpec* wearer = nullptr;
  for (const auto& o : obstacles)
    if (o.character && (o.group.empty() || o.group == g.group)) {
      if (wearer) return nullptr;
      wearer = &o;
    }
  return wearer;
}

std::string missing_joint(const Skeleton& skeleton, const std::string& joint);

// The project's figure as garments are sized for, with a body made as `body` makes the wearer's
// (so the two are measured alike); `bodies` keeps its polygonized body for the next wearer.
FigureMeasure reference_figure(const BodyParams& body, BodyMeshCache& bodies) {
  Motion figure;
  figure.skeleton = figure_skeleton();
  figure.frames.assign(1, std::vector<double>(static_cast<std::size_t>(figure.skeleton.num_channels), 0.0));
  BodyParams as_made = body;
  as_made.build = 1.0;
  const Body made(figure, as_made, &bodies);
  const Pose rest = Body::rest_pose(figure.skeleton);
  return measure_figure(figure, rest, made.rest_mesh(), made.skin(rest), made.main_joints());
}

// The procedural garments a character wears made again for it, in the pose they are put on in
// (fitting.hpp), each cut in the same rows so its handles hold the same nodes.
// `start_time` and `shot` bound the run's time: the arms' reach is taken over it.
void fit_garments(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments, const std::vector<GarmentMaking>& making,
                  const std::vector<std::size_t>& worn, const Character& wearer, const std::string& wearer_name, double start_time,
                  double shot, BodyMeshCache& bodies) {
  const Pose& pose = wearer.dressing_pose();
  const JsonValue& first = entries[worn.front()];
  std::optional<GarmentFit> fit;
  std::optional<FigureMeasure> figure;
  const FigureMeasure reference = reference_figure(wearer.body_params(), bodies);
  try {
    figure = measure_figure(wearer.motion(), pose, wearer.rest_mesh(), wearer.skinned(pose), wearer.main_joints());
    fit.emplace(reference, *figure);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const bool joint = what.find(' ') == std::string::npos;
    (first.has("fit") ? first.at("fit") : first)
        .fail("cannot fit the garment to character '" + wearer_name + "': " + (joint ? missing_joint(wearer.motion().skeleton, what) : what) +
              " (or set \"fit\": false)");
  }
  if (fit->identity()) return;
  // Held nodes must stay clear of the arms: their reach over the motion, when anything is held.
  std::vector<HeldGarment> held;
  for (std::size_t g : worn) {
    HeldGarment& h = held.emplace_back(HeldGarment{*making[g].pattern, {}});
    const auto& which = garments[g].mesh.node_attrs().get<int32_t>(kHandleAttr);
    for (NodeId n : garments[g].mesh.nodes())
      if (which[n] >= 0) h.held.push_back(n.idx);
  }
  double ease = 1.0;
  if (std::any_of(held.begin(), held.end(), [](const HeldGarment& h) { return !h.held.empty(); })) {
    std::vector<Pose> moving;
    const double end = std::min(shot, wearer.start() + wearer.motion().duration() / wearer.speed());  // held after
    for (double t : sample_times(start_time, std::max(start_time, end), kPoseSampleTime)) moving.push_back(wearer.pose_at(t));
    measure_arm_reach(*figure, wearer.motion(), pose, wearer.rest_mesh(), wearer.main_joints(), moving,
                      [&](const Pose& p) { return wearer.skinned(p); });
    fit.emplace(reference, *figure);
    ease = fit->ease_clearing_arms(held, kArmClearance);
  }
  std::vector<GarmentPattern> patterns;
  for (std::size_t g : worn) patterns.push_back(*making[g].pattern);
  const std::vector<GarmentPattern> fitted = fit->fit(patterns, ease);
  for (std::size_t k = 0; k < worn.size(); ++k) {
    const std::size_t g = worn[k];
    GarmentSpec& garment = garments[g];
    MeshSource source = std::visit([](const auto& p) { return make_garment(p); }, fitted[k]);
    for (Vec3& x : source.positions) x = fit->place(x);
    Mesh mesh = build_mesh(source);
    if (mesh.num_nodes() != garment.mesh.num_nodes() || mesh.num_faces() != garment.mesh.num_faces())
      throw std::logic_error("a fitted garment has other nodes than the garment it fits");
    if (making[g].transform)
      for (NodeId n : mesh.nodes()) mesh.x(n) = making[g].transform->apply(mesh.x(n));
    if (making[g].rest_initial) set_rest_angles_from_world(mesh);
    mesh.node_attrs().add<int32_t>(kHandleAttr, -1);
    mesh.node_attrs().add<Vec3>(kAnchorAttr, Vec3::Zero());
    const auto& chosen = garment.mesh.node_attrs().get<int32_t>(kHandleAttr);
    for (NodeId n : mesh.nodes())
      if (chosen[n] >= 0) hold_node(mesh, n, chosen[n]);
    garment.mesh = std::move(mesh);
    garment.fitted_to = wearer_name;
    garment.ease = ease;
  }
}

// Why find_joint found no `joint`: the names tried and the first of the motion's joints.
std::string missing_joint(const Skeleton& skeleton, const std::string& joint) {
  std::string msg = "the motion has no joint '" + joint + "'";
  const std::vector<std::string> aliases = joint_aliases(joint);
  if (!aliases.empty()) {
    msg += " (nor";
    for (std::size_t k = 0; k < aliases.size(); ++k) msg += (k ? ", " : " ") + aliases[k];
    msg += ")";
  }
  msg += "; its joints:";
  std::size_t listed = 0;
  for (const Joint& j : skeleton.joints) {
    if (j.end_site) continue;
    if (listed == 8) {
      msg += " ...";
      break;
    }
    msg += (listed++ ? ", " : " ") + j.name;
  }
  return msg + " (a character's joint_names renames a capture's joints)";
}

// `shot` is the scene's length (s): a character's build looks at the poses it takes in the shot.
ObstacleSpec parse_obstacle(const JsonValue& j, const std::string& scene_path, double frame_time, double shot, BodyMeshCache& bodies) {
  j.only_keys({"name", "group", "mesh", "character", "transform", "motion"});
  ObstacleSpec o;
  o.name = j.at("name").string();
  o.group = j.string_or("group", "");
  if (j.has("mesh") == j.has("character")) j.fail("an obstacle needs exactly one of \"mesh\" and \"character\"");
  if (auto c = j.find("character")) {
    // The character places itself (its transform applies to the skinned body every frame).
    c->only_keys({"motion", "skin", "scale", "build", "resolution", "start", "speed", "recenter", "joint_names", "first_frame", "preroll",
                  "mirror"});
    const JsonValue file = c->at("motion");
    const std::string path = resolve(file, scene_path);
    Motion motion = with_key(file, [&] { return read_bvh(path); });
    if (motion.frames.empty()) file.fail("the motion has no frames");
    if (auto names = c->find("joint_names")) {
      std::map<std::string, std::string> renames;
      for (const auto& [from, to] : names->members()) {
        const std::string name = to.string();
        if (name.empty()) to.fail("a joint's new name must not be empty");
        renames[from] = name;
      }
      try {
        rename_joints(motion.skeleton, renames);
      } catch (const std::invalid_argument& e) {
        names->fail(std::string("the motion has no joint '") + e.what() + "' to rename");
      }
    }
    if (c->boolean_or("mirror", false)) {
      try {
        motion = mirrored(motion);
      } catch (const std::invalid_argument& e) {
        c->at("mirror").fail(std::string("cannot mirror the motion: ") + e.what());
      }
    }
    const double scale = c->positive_or("scale", 1.0);
    scale_lengths(motion, scale);
    check_figure_size(motion, scale, c->has("scale") ? c->at("scale") : file);
    std::optional<MeshSource> skin;
    if (auto s = c->find("skin")) {
      const std::string skin_path = resolve(*s, scene_path);
      skin = with_key(*s, [&] {
        read_obj(skin_path, false);  // checked as any obstacle mesh: manifold, consistently oriented
        return read_obj_source(skin_path, false);
      });
      for (Vec3& x : skin->positions) x *= scale;
    }
    // The shot starts at `first_frame`, by default after the capture's leading reference frames
    // (its T-pose), which are then the pose the garments are made in (dressing.hpp).
    const int reference = leading_reference_frames(motion);
    int first = reference;
    if (auto f = c->find("first_frame")) {
      const long long k = f->integer();
      if (k < 0 || k >= static_cast<long long>(motion.frames.size()))
        f->fail("must be between 0 and " + std::to_string(motion.frames.size() - 1) + " (the motion's last frame)");
      first = static_cast<int>(k);
    }
    if (c->boolean_or("recenter", true)) {
      const Vec3 shift = recentering(motion, first);
      motion.skeleton.joints.front().offset -= shift;
      if (skin)
        for (Vec3& x : skin->positions) x -= shift;
    }
    Dressing dressing;
    dressing.pose = dressing_pose(motion, std::min(reference, first), first);
    motion.frames.erase(motion.frames.begin(), motion.frames.begin() + first);
    // A capture that does not start in the dressing pose moves into it over a second by default.
    const double apart = largest_joint_distance(motion, *dressing.pose, motion.frame_pose(0));
    dressing.preroll = c->has("preroll") ? c->at("preroll").non_negative() : apart > kStillDistance ? kDefaultPreroll : 0.0;
    if (dressing.preroll > kLongestPreroll) c->at("preroll").fail("must be at most 60 s");
    BodyParams body;
    body.resolution = c->positive_or("resolution", body.resolution);
    if (body.resolution < 0.005) c->at("resolution").fail("must be at least 0.005 m");
    const double start = c->number_or("start", 0.0), speed = c->positive_or("speed", 1.0);
    // By default as built as the project's figure, or slimmer if its arms would otherwise pass
    // through its body where the garments are put on or anywhere in the shot.
    if (c->has("build")) {
      body.build = c->at("build").positive();
    } else {
      std::vector<Pose> poses = clip_poses(MotionClip{&motion, start, speed}, 0.0, shot, kPoseSampleTime);
      poses.push_back(*dressing.pose);
      body.build = build_clearing_arms(motion, poses, kArmClearance);
    }
    const Transform placement = j.has("transform") ? parse_transform(j.at("transform")) : Transform{};
    o.character = std::make_shared<const Character>(std::move(motion), body, placement, start, speed, std::move(skin), std::move(dressing),
                                                     &bodies);
    o.mesh = build_mesh(o.character->rest_mesh());
    const std::vector<Vec3> x0 = o.character->positions_at(0.0);
    for (NodeId n : o.mesh.nodes()) o.mesh.x(n) = x0[static_cast<std::size_t>(n.idx)];
  } else if (auto seq = j.at("mesh").is_string() ? std::nullopt : j.at("mesh").find("sequence")) {
    const JsonValue mesh = j.at("mesh");
    mesh.only_keys({"sequence"});
    seq->only_keys({"files", "first", "count", "frame_time"});
    const long long first = seq->integer_or("first", 1), count = seq->at("count").integer();
    if (count < 1 || count > 1'000'000) seq->at("count").fail("must be between 1 and 1,000,000");
    if (first < 0 || first > 1'000'000'000) seq->at("first").fail("must be between 0 and 1,000,000,000");
    const double dt = seq->positive_or("frame_time", frame_time);
    const JsonValue files = seq->at("files");
    std::string pattern = files.string();
    if (pattern.empty()) files.fail("empty file pattern");
    if (!fs::path(pattern).is_absolute()) pattern = (fs::path(scene_path).parent_path() / pattern).string();
    ObjSequence s = with_key(files, [&] {
      std::vector<std::string> names = sequence_files(pattern, static_cast<int>(first), static_cast<int>(count));
      for (const auto& n : names)
        if (std::error_code ec; !fs::is_regular_file(n, ec))
          throw InputError(n, "", "file not found (frame " + std::to_string(&n - names.data() + first) + " of the sequence)");
      return load_obj_sequence(names, dt);
    });
    o.mesh = std::move(s.mesh);
    o.sequence = std::move(s.frames);
    o.sequence_frame_time = dt;
  } else {
    o.mesh = parse_mesh(j.at("mesh"), scene_path, false);
  }
  if (auto t = j.find("transform"); t && !o.character) {
    Transform tr = parse_transform(*t);
    for (NodeId n : o.mesh.nodes()) o.mesh.x(n) = tr.apply(o.mesh.x(n));
    for (auto& frame : o.sequence)
      for (Vec3& x : frame) x = tr.apply(x);
  }
  o.rest.resize(static_cast<std::size_t>(o.mesh.node_capacity()));
  Vec3 centre = Vec3::Zero();
  for (NodeId n : o.mesh.nodes()) {
    o.rest[static_cast<std::size_t>(n.idx)] = o.mesh.x(n);
    centre += o.mesh.x(n);
  }
  o.pivot = centre / std::max(1, o.mesh.num_nodes());
  if (auto m = j.find("motion")) {
    m->only_keys({"translate", "rotate"});
    if (auto tr = m->find("translate")) o.translate = parse_track(*tr, "offset");
    if (auto ro = m->find("rotate")) o.rotate = parse_track(*ro, "degrees");
  }
  return o;
}

// The `camera` block: lens parameters and keyframes [{"time", "position", "target", "cut"}].
CameraPath parse_camera(const JsonValue& j) {
  j.only_keys({"fov", "width", "height", "near", "far", "up", "keys", "focus_distance", "f_stop", "sensor_height", "shutter"});
  Camera lens;
  lens.fov_y_degrees = j.positive_or("fov", lens.fov_y_degrees);
  if (lens.fov_y_degrees >= 180) j.at("fov").fail("must be below 180 degrees");
  const long long w = j.integer_or("width", lens.width), h = j.integer_or("height", lens.height);
  if (w < 1 || w > 100000) j.at("width").fail("must be between 1 and 100000 pixels");
  if (h < 1 || h > 100000) j.at("height").fail("must be between 1 and 100000 pixels");
  lens.width = static_cast<int>(w);
  lens.height = static_cast<int>(h);
  lens.near = j.positive_or("near", lens.near);
  lens.far = j.positive_or("far", lens.far);
  if (lens.far <= lens.near) j.at("far").fail("must be beyond near");
  lens.up = j.vec3_or("up", lens.up);
  if (lens.up.norm() == 0) j.at("up").fail("must not be zero");
  const auto focus = j.find("focus_distance");
  lens.focus_on_target = focus && focus->is_string();
  if (lens.focus_on_target && focus->string() != "target")
    focus->fail("expected a distance in metres, or \"target\" for the focus to follow the camera's target");
  if (!lens.focus_on_target) lens.focus_distance = j.non_negative_or("focus_distance", lens.focus_distance);
  lens.f_stop = j.positive_or("f_stop", lens.f_stop);
  if (lens.f_stop < 0.5 || lens.f_stop > 256) j.at("f_stop").fail("must be between 0.5 and 256");
  lens.sensor_height_mm = j.positive_or("sensor_height", lens.sensor_height_mm);
  if (lens.sensor_height_mm > 1000) j.at("sensor_height").fail("must be at most 1000 (millimetres)");
  if (lens.focus_distance > 0 && lens.focus_distance <= 1e-3 * lens.focal_length_mm())
    j.at("focus_distance").fail("must be beyond the focal length (" + std::to_string(lens.focal_length_mm()) + " mm), or 0 for no depth of field");
  lens.shutter = j.non_negative_or("shutter", lens.shutter);
  if (lens.shutter > 1) j.at("shutter").fail("must be at most 1 (the whole frame time)");
  std::vector<CameraKey> keys;
  const JsonValue list = j.at("keys");
  for (const JsonValue& k : list.items()) {
    k.only_keys({"time", "position", "target", "cut"});
    CameraKey key;
    key.time = k.at("time").non_negative();
    key.position = k.at("position").vec3();
    key.target = k.at("target").vec3();
    if (auto cut = k.find("cut")) key.cut = cut->boolean();
    if (!keys.empty() && !(key.time > keys.back().time)) k.at("time").fail("keyframe times must increase");
    if ((key.target - key.position).norm() == 0) k.at("target").fail("must differ from the position");
    if (((key.target - key.position).normalized().cross(lens.up.normalized())).norm() < 1e-6)
      k.at("target").fail("the view direction is parallel to the camera's up vector");
    keys.push_back(key);
  }
  if (keys.empty()) list.fail("a camera needs at least one key");
  return CameraPath(lens, std::move(keys));
}

// The `view` block: parameters of view-dependent sizing.
ViewParams parse_view(const JsonValue& j) {
  j.only_keys({"v_back", "v_out", "margin", "anticipation", "lead", "linger", "l_min", "l_max", "silhouette_threshold", "settle",
               "back_occlusion", "occlusion_scale", "occlusion_erosion", "occlusion_depth", "motion_anticipation", "defocus_scale",
               "motion_blur_scale", "occlusion", "v_occluded", "floor_in_frame", "fold_length", "fold_time", "gathering",
               "keep_compression", "coarse_damping"});
  ViewParams p;
  p.v_back = j.positive_or("v_back", p.v_back);
  p.v_out = j.positive_or("v_out", p.v_out);
  if (p.v_back > 1) j.at("v_back").fail("must be at most 1");
  if (p.v_out > p.v_back) j.at("v_out").fail("must be at most v_back");
  p.margin = j.positive_or("margin", p.margin);
  p.anticipation = j.non_negative_or("anticipation", p.anticipation);
  p.lead = j.non_negative_or("lead", p.lead);
  p.linger = j.non_negative_or("linger", p.linger);
  p.l_min = j.non_negative_or("l_min", p.l_min);
  p.l_max = j.non_negative_or("l_max", p.l_max);
  if (p.l_max > 0 && p.l_max < p.l_min) j.at("l_max").fail("must be 0 (no ceiling) or at least l_min");
  p.silhouette_threshold = j.positive_or("silhouette_threshold", p.silhouette_threshold);
  p.settle = j.non_negative_or("settle", p.settle);
  p.back_occlusion = j.boolean_or("back_occlusion", p.back_occlusion);
  p.occlusion_scale = j.positive_or("occlusion_scale", p.occlusion_scale);
  if (p.occlusion_scale > 1) j.at("occlusion_scale").fail("must be at most 1 (the camera's own image size)");
  const long long erosion = j.integer_or("occlusion_erosion", p.occlusion_erosion);
  if (erosion < 0 || erosion > 16) j.at("occlusion_erosion").fail("must be an integer from 0 to 16 (pixels)");
  p.occlusion_erosion = static_cast<int>(erosion);
  p.occlusion_depth = j.non_negative_or("occlusion_depth", p.occlusion_depth);
  p.occlusion = j.boolean_or("occlusion", p.occlusion);
  p.floor_in_frame = j.boolean_or("floor_in_frame", p.floor_in_frame);
  p.fold_length = j.non_negative_or("fold_length", p.fold_length);
  p.fold_time = j.non_negative_or("fold_time", p.fold_time);
  p.gathering = j.non_negative_or("gathering", p.gathering);
  if (p.gathering > 1) j.at("gathering").fail("must be at most 1 (the material's own stiffness)");
  p.keep_compression = j.boolean_or("keep_compression", p.keep_compression);
  p.coarse_damping = j.non_negative_or("coarse_damping", p.coarse_damping);
  if (p.coarse_damping > 10) j.at("coarse_damping").fail("must be at most 10 (time steps)");
  p.v_occluded = j.positive_or("v_occluded", p.v_back);
  if (p.v_occluded > 1) j.at("v_occluded").fail("must be at most 1");
  if (p.v_occluded < p.v_out) j.at("v_occluded").fail("must be at least v_out");
  p.motion_anticipation = j.boolean_or("motion_anticipation", p.motion_anticipation);
  p.defocus_scale = j.non_negative_or("defocus_scale", p.defocus_scale);
  p.motion_blur_scale = j.non_negative_or("motion_blur_scale", p.motion_blur_scale);
  return p;
}

void check_name(const JsonValue& where, const std::string& name, std::set<std::string>& seen) {
  if (name.empty() || name.find_first_of("/\\ \t.") != std::string::npos)
    where.fail("names must be non-empty, without spaces, dots or slashes (they name output files)");
  if (!seen.insert(name).second) where.fail("name '" + name + "' is used twice");
}

}  // namespace

Scene load_scene(const std::string& path) {
  JsonValue j = JsonValue::load_file(path);
  j.only_keys({"name", "frame_time", "frames", "substeps", "gravity", "air", "solver", "remeshing", "collision", "garments", "obstacles", "crowds", "camera",
               "view"});
  Scene s;
  s.path = path;
  s.name = j.string_or("name", fs::path(path).stem().string());
  // The name is the default output directory's (out/NAME): one path component, nothing else.
  const bool control = std::any_of(s.name.begin(), s.name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  if (s.name.empty() || s.name == "." || s.name == ".." || s.name.find_first_of("/\\") != std::string::npos || control)
    (j.has("name") ? j.at("name") : j).fail("the scene's name must be one file name (no slashes, not . or ..): it names the output directory");
  s.frame_time = j.has("frame_time") ? j.at("frame_time").positive() : s.frame_time;
  const long long frames = j.integer_or("frames", s.frames);
  if (frames < 1 || frames > 10'000'000) j.at("frames").fail("must be between 1 and 10,000,000");
  s.frames = static_cast<int>(frames);
  long long sub = j.integer_or("substeps", s.substeps);
  if (sub < 1 || sub > 10000) j.at("substeps").fail("must be between 1 and 10000");
  s.substeps = static_cast<int>(sub);
  s.gravity = j.vec3_or("gravity", s.gravity);
  if (auto a = j.find("air")) {
    a->only_keys({"damping", "drag", "wind"});
    s.air.damping = a->non_negative_or("damping", 0.0);
    s.air.drag = a->non_negative_or("drag", 0.0);
    s.air.wind = a->vec3_or("wind", Vec3::Zero());
  }
  if (auto so = j.find("solver")) {
    so->only_keys({"linear", "cg_tolerance", "cg_max_iterations", "max_velocity_change"});
    if (auto lin = so->find("linear"))
      if (!parse_linear_solver_kind(lin->string(), s.solver.linear)) lin->fail("expected \"cholmod-pcg\", \"cholmod\", \"ldlt\" or \"cg\"");
    s.solver.params.cg_tolerance = so->positive_or("cg_tolerance", s.solver.params.cg_tolerance);
    long long it = so->integer_or("cg_max_iterations", s.solver.params.cg_max_iterations);
    if (it < 1 || it > 1'000'000) so->at("cg_max_iterations").fail("must be between 1 and 1,000,000");
    s.solver.params.cg_max_iterations = static_cast<int>(it);
    s.solver.max_velocity_change = so->positive_or("max_velocity_change", s.solver.max_velocity_change);
  }
  if (auto r = j.find("remeshing")) {
    r->only_keys({"refine_angle", "refine_velocity", "refine_compression", "size", "aspect_min", "fixed_size"});
    auto& p = s.remeshing;
    p.refine_angle = r->positive_or("refine_angle", p.refine_angle);
    p.refine_velocity = r->positive_or("refine_velocity", p.refine_velocity);
    p.refine_compression = r->positive_or("refine_compression", p.refine_compression);
    if (auto size = r->find("size")) {
      Vec2 range = size->vec2();
      if (!(range.x() > 0 && range.y() >= range.x())) size->fail("expected [min, max] with 0 < min <= max (metres)");
      p.size_min = range.x();
      p.size_max = range.y();
    }
    p.aspect_min = r->positive_or("aspect_min", p.aspect_min);
    if (p.aspect_min > 1) r->at("aspect_min").fail("must be at most 1");
    s.fixed_size = r->positive_or("fixed_size", 0.0);
  }
  if (auto c = j.find("collision")) {
    c->only_keys({"thickness", "impact_separation", "max_iterations", "untangle_iterations", "repulsion_thickness", "repulsion_stiffness",
                   "friction"});
    s.collision.thickness = c->positive_or("thickness", s.collision.thickness);
    s.collision.impact_separation = c->positive_or("impact_separation", 0.1 * s.collision.thickness);
    if (s.collision.impact_separation > s.collision.thickness)
      c->at("impact_separation").fail("must be at most the thickness");
    s.collision.repulsion_thickness = c->positive_or("repulsion_thickness", 2 * s.collision.thickness);
    if (s.collision.repulsion_thickness < s.collision.thickness)
      c->at("repulsion_thickness").fail("must be at least the thickness");
    s.collision.repulsion_stiffness = c->positive_or("repulsion_stiffness", s.collision.repulsion_stiffness);
    s.collision.friction = c->non_negative_or("friction", s.collision.friction);
    long long it = c->integer_or("max_iterations", s.collision.max_iterations);
    if (it < 1 || it > 1000) c->at("max_iterations").fail("must be between 1 and 1000");
    s.collision.max_iterations = static_cast<int>(it);
    long long untangle = c->integer_or("untangle_iterations", s.collision.untangle_iterations);
    if (untangle < 0 || untangle > 10000) c->at("untangle_iterations").fail("must be between 0 and 10000");
    s.collision.untangle_iterations = static_cast<int>(untangle);
  }
  std::set<std::string> names;
  std::vector<GarmentMaking> making;
  const SceneEntries entries = scene_entries(j);  // the garments and obstacles, crowds' copies included
  for (const JsonValue& g : entries.garments) {
    s.garments.push_back(parse_garment(g, path, making.emplace_back()));
    check_name(g.at("name"), s.garments.back().name, names);
  }
  if (s.garments.empty())
    (j.has("garments") ? j.at("garments") : j).fail("a scene needs at least one garment: \"garments\" lists none and no crowd makes one");
  BodyMeshCache bodies;  // a crowd's copies share their figure's body
  for (const JsonValue& o : entries.obstacles) {
    s.obstacles.push_back(parse_obstacle(o, path, s.frame_time, s.frames * s.frame_time, bodies));
    check_name(o.at("name"), s.obstacles.back().name, names);
  }
  // The run starts before the shot by the longest pre-roll, characters in their dressing poses,
  // each garment made for the character wearing it.
  double preroll = 0;
  for (const auto& o : s.obstacles)
    if (o.character) preroll = std::max(preroll, o.character->preroll());
  s.preroll_frames = static_cast<int>(std::ceil(preroll / s.frame_time - 1e-9));
  if (s.preroll_frames > 0)
    for (auto& o : s.obstacles)
      if (o.character) {
        const std::vector<Vec3> x = o.character->positions_at(s.start_time());
        for (NodeId n : o.mesh.nodes()) o.mesh.x(n) = x[static_cast<std::size_t>(n.idx)];
      }
  std::vector<std::pair<const ObstacleSpec*, std::vector<std::size_t>>> worn;  // by wearer, in scene order
  for (std::size_t gi = 0; gi < s.garments.size(); ++gi)
    if (const ObstacleSpec* wearer = garment_wearer(entries.garments[gi], s.garments[gi], making[gi], s.obstacles)) {
      auto it = std::find_if(worn.begin(), worn.end(), [&](const auto& w) { return w.first == wearer; });
      if (it == worn.end()) it = worn.insert(worn.end(), {wearer, {}});
      it->second.push_back(gi);
    }
  for (const auto& [wearer, garments] : worn)
    fit_garments(entries.garments, s.garments, making, garments, *wearer->character, wearer->name, s.start_time(), s.frames * s.frame_time,
                 bodies);
  // Handles attached to a character's joint, now that the obstacles are known.
  for (std::size_t gi = 0; gi < s.garments.size(); ++gi) {
    const JsonValue& garment = entries.garments[gi];
    if (!garment.has("handles")) continue;
    const auto handles = garment.at("handles").items();
    for (std::size_t hi = 0; hi < handles.size(); ++hi) {
      const auto attach = handles[hi].find("attach");
      if (!attach) continue;
      attach->only_keys({"obstacle", "joint"});
      const std::string obstacle = attach->at("obstacle").string(), joint = attach->at("joint").string();
      const auto o = std::find_if(s.obstacles.begin(), s.obstacles.end(), [&](const ObstacleSpec& x) { return x.name == obstacle; });
      if (o == s.obstacles.end()) attach->at("obstacle").fail("no obstacle named '" + obstacle + "'");
      if (!o->character) attach->at("obstacle").fail("'" + obstacle + "' is not a character");
      if (o->group != s.garments[gi].group) attach->at("obstacle").fail("'" + obstacle + "' is in another group than the garment");
      const Skeleton& skeleton = o->character->motion().skeleton;
      const std::optional<int> found = find_joint(skeleton, joint);
      if (!found) attach->at("joint").fail(missing_joint(skeleton, joint));
      ClothHandle& handle = s.garments[gi].handles[hi];
      handle.character = o->character;
      handle.joint = *found;
      handle.from_start = handle.character->joint_transform(handle.joint, s.start_time()).inverse();
    }
  }
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const std::string& group = s.obstacles[k].group;
    if (!group.empty() && std::none_of(s.garments.begin(), s.garments.end(), [&](const GarmentSpec& g) { return g.group == group; }))
      entries.obstacles[k].at("group").fail("no garment is in group '" + group + "'");
  }
  if (auto c = j.find("camera")) s.camera = parse_camera(*c);
  if (auto v = j.find("view")) s.view = parse_view(*v);
  return s;
}

namespace {

// The garments' groups in order of first appearance ("" for garments of no group).
std::vector<std::string> garment_groups(const std::vector<GarmentSpec>& garments) {
  std::vector<std::string> groups;
  for (const auto& g : garments)
    if (std::find(groups.begin(), groups.end(), g.group) == groups.end()) groups.push_back(g.group);
  return groups;
}

}  // namespace

void apply_perturbation(Scene& scene, const Perturbation& p) {
  scene.gravity *= 1 + p.gravity;
  scene.remeshing.resolution_scale *= 1 + p.resolution;
}

std::vector<Scene> split_groups(Scene scene) {
  std::vector<GarmentSpec> garments = std::move(scene.garments);
  std::vector<ObstacleSpec> obstacles = std::move(scene.obstacles);
  scene.garments.clear();
  scene.obstacles.clear();  // `scene` now holds the settings every part shares
  const std::vector<std::string> groups = garment_groups(garments);
  std::vector<Scene> parts(groups.size(), scene);
  // Each garment goes to its group's part once (matching after a move would match the
  // moved-from garment's emptied group to the part of no group).
  for (auto& g : garments) {
    const auto k = static_cast<std::size_t>(std::find(groups.begin(), groups.end(), g.group) - groups.begin());
    parts[k].garments.push_back(std::move(g));
  }
  std::vector<std::shared_ptr<const ObstacleSpec>> shared;
  for (const auto& o : obstacles) shared.push_back(o.group.empty() ? nullptr : std::make_shared<const ObstacleSpec>(o));
  for (std::size_t k = 0; k < groups.size(); ++k)
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
      if (obstacles[i].group == groups[k] || obstacles[i].group.empty()) parts[k].obstacles.push_back(obstacles[i]);
      else parts[k].hiding.push_back(shared[i]);
    }
  return parts;
}

std::vector<double> group_faces(const Scene& scene) {
  const std::vector<std::string> groups = garment_groups(scene.garments);
  std::vector<double> faces(groups.size(), 0.0);
  for (const auto& g : scene.garments)
    faces[static_cast<std::size_t>(std::find(groups.begin(), groups.end(), g.group) - groups.begin())] += g.mesh.num_faces();
  return faces;
}

Scene keep_groups(Scene scene, const std::vector<std::string>& groups) {
  const std::vector<std::string> present = garment_groups(scene.garments);
  for (const std::string& group : groups)
    if (group.empty() || std::find(present.begin(), present.end(), group) == present.end()) {
      std::string known;
      for (const std::string& p : present)
        if (!p.empty()) known += (known.empty() ? "" : ", ") + p;
      throw std::invalid_argument("no garment group '" + group + "' (" + (known.empty() ? "the scene's garments have no groups" : "its groups: " + known) + ")");
    }
  auto wanted = [&](const std::string& group) { return std::find(groups.begin(), groups.end(), group) != groups.end(); };
  std::erase_if(scene.garments, [&](const GarmentSpec& g) { return !wanted(g.group); });
  const auto others = std::stable_partition(scene.obstacles.begin(), scene.obstacles.end(),
                                            [&](const ObstacleSpec& o) { return o.group.empty() || wanted(o.group); });
  for (auto o = others; o != scene.obstacles.end(); ++o) scene.hiding.push_back(std::make_shared<const ObstacleSpec>(std::move(*o)));
  scene.obstacles.erase(others, scene.obstacles.end());
  return scene;
}

}  // namespace vdc

namespace vdc {

std::pair<Vec3, double> ObstacleSpec::reach_at(double t) const {
  if (character && translate.empty() && rotate.empty()) return character->reach_at(t);
  return {Vec3::Zero(), -1.0};
}

std::vector<Vec3> ObstacleSpec::positions_at(double t) const {
  std::vector<Vec3> out = character ? character->positions_at(t) : sequence.size() > 1 ? interpolate_frames(sequence, sequence_frame_time, t) : rest;
  if (translate.empty() && rotate.empty()) return out;  // no rigid motion: the positions as they are
  Transform motion;
  motion.rotate_degrees = rotate.at(t);
  const Mat3 r = motion.rotation();
  const Vec3 offset = translate.at(t);
  for (Vec3& x : out) x = r * (x - pivot) + pivot + offset;
  return out;
}

}  // namespace vdc
