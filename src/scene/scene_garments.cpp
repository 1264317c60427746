// The `garments[i]` entries and their `handles[j]` (docs/scene-format.md): a garment's mesh,
// material, placement and rest shape, and the nodes its handles hold.
#include "scene/scene_blocks.hpp"

#include <algorithm>
#include <limits>

#include "physics/cloth_model.hpp"
#include "scene/joint_names.hpp"
#include "scene/material_file.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

Material parse_material_ref(const JsonValue& j, const std::string& scene_path) {
  if (j.is_string()) {
    std::string file = resolve_file(j, scene_path);
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

// The nodes of the garment inside a handle's `box`, [[x0, y0, z0], [x1, y1, z1]].
void nodes_in_box(const JsonValue& box, const Mesh& mesh, std::vector<NodeId>& nodes) {
  const auto corners = box.items();
  if (corners.size() != 2) box.fail("expected [[x0, y0, z0], [x1, y1, z1]]");
  const Vec3 lo = corners[0].vec3(), hi = corners[1].vec3();
  if (!(lo.array() <= hi.array()).all()) box.fail("the first corner must be the lower one on every axis");
  std::size_t before = nodes.size();
  for (NodeId n : mesh.nodes())
    if ((mesh.x(n).array() >= lo.array()).all() && (mesh.x(n).array() <= hi.array()).all()) nodes.push_back(n);
  if (nodes.size() == before) box.fail("no node of the garment is in the box");
}

// The nodes a handle holds: by index, nearest to points in space or in the pattern, in a box.
std::vector<NodeId> handle_nodes(const JsonValue& h, const Mesh& mesh) {
  std::vector<NodeId> nodes;
  if (auto ids = h.find("nodes"))
    for (const JsonValue& id : ids->items()) {
      long long i = id.integer();
      if (i < 0 || i >= mesh.num_nodes()) id.fail("node index out of range (the mesh has " + std::to_string(mesh.num_nodes()) + " nodes)");
      nodes.push_back(NodeId(static_cast<int32_t>(i)));
    }
  if (auto pts = h.find("points"))
    for (const JsonValue& p : pts->items()) nodes.push_back(nearest_node(mesh, p.vec3()));
  if (auto uvs = h.find("uv"))
    for (const JsonValue& u : uvs->items()) nodes.push_back(nearest_vert_node(mesh, u.vec2()));
  if (auto box = h.find("box")) nodes_in_box(*box, mesh, nodes);
  if (nodes.empty()) h.fail("a handle needs at least one of nodes, points, uv or box");
  return nodes;
}

void parse_handles(const JsonValue& list, GarmentSpec& g) {
  const auto& which = g.mesh.node_attrs().get<int32_t>(kHandleAttr);
  for (const JsonValue& h : list.items()) {
    h.only_keys({"nodes", "points", "uv", "box", "release", "path", "attach"});
    ClothHandle handle;
    handle.release = h.has("release") ? h.at("release").non_negative() : std::numeric_limits<double>::infinity();
    if (auto path = h.find("path")) handle.path = parse_track(*path, "offset");
    const std::vector<NodeId> nodes = handle_nodes(h, g.mesh);
    const auto index = static_cast<int32_t>(g.handles.size());
    for (NodeId n : nodes) {
      if (which[n] >= 0 && which[n] != index) h.fail("node " + std::to_string(n.idx) + " already belongs to another handle");
      hold_node(g.mesh, n, index);
    }
    g.handles.push_back(handle);
  }
}

// A handle's `attach`: the character's joint it follows.
void attach_handle(const JsonValue& attach, const GarmentSpec& garment, ClothHandle& handle, const std::vector<ObstacleSpec>& obstacles,
                   double start_time) {
  attach.only_keys({"obstacle", "joint"});
  const std::string obstacle = attach.at("obstacle").string(), joint = attach.at("joint").string();
  const auto o = std::find_if(obstacles.begin(), obstacles.end(), [&](const ObstacleSpec& x) { return x.name == obstacle; });
  if (o == obstacles.end()) attach.at("obstacle").fail("no obstacle named '" + obstacle + "'");
  if (!o->character) attach.at("obstacle").fail("'" + obstacle + "' is not a character");
  if (o->group != garment.group) attach.at("obstacle").fail("'" + obstacle + "' is in another group than the garment");
  const Skeleton& skeleton = o->character->motion().skeleton;
  const std::optional<int> found = find_joint(skeleton, joint);
  if (!found) attach.at("joint").fail(missing_joint(skeleton, joint));
  handle.character = o->character;
  handle.joint = *found;
  handle.from_start = handle.character->joint_transform(handle.joint, start_time).inverse();
}

}  // namespace

void hold_node(Mesh& mesh, NodeId n, int32_t index) {
  mesh.node_attrs().get<int32_t>(kHandleAttr)[n] = index;
  mesh.node_attrs().get<Vec3>(kAnchorAttr)[n] = mesh.x(n);
  mesh.flags(n) |= kNodeHandle;
}

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

void attach_handles(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments, const std::vector<ObstacleSpec>& obstacles,
                    double start_time) {
  for (std::size_t gi = 0; gi < garments.size(); ++gi) {
    const JsonValue& garment = entries[gi];
    if (!garment.has("handles")) continue;
    const auto handles = garment.at("handles").items();
    for (std::size_t hi = 0; hi < handles.size(); ++hi)
      if (const auto attach = handles[hi].find("attach"))
        attach_handle(*attach, garments[gi], garments[gi].handles[hi], obstacles, start_time);
  }
}

}  // namespace vdc
