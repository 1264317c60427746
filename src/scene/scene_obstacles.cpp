// The `obstacles[i]` entries (docs/scene-format.md): a mesh, an OBJ sequence or an animated
// character, placed by its transform and moved rigidly by its motion.
#include "scene/scene_blocks.hpp"

#include <algorithm>
#include <filesystem>

#include "core/mesh_build.hpp"
#include "scene/obj_sequence.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

// The character places itself (its transform applies to the skinned body every frame).
void read_character(const JsonValue& j, const JsonValue& c, const std::string& scene_path, double shot, BodyMeshCache& bodies,
                    ObstacleSpec& o) {
  o.character = parse_character(c, j.find("transform"), scene_path, shot, bodies, o.notes);
  try {
    o.mesh = build_mesh(o.character->rest_mesh());
  } catch (const MeshBuildError& e) {
    c.fail(std::string("its skin cannot be a collision surface: ") + e.what());
  }
  const std::vector<Vec3> x0 = o.character->positions_at(0.0);
  for (NodeId n : o.mesh.nodes()) o.mesh.x(n) = x0[static_cast<std::size_t>(n.idx)];
}

// `{"sequence": {...}}`: one OBJ file a frame.
void read_sequence(const JsonValue& mesh, const JsonValue& seq, const std::string& scene_path, double frame_time, ObstacleSpec& o) {
  mesh.only_keys({"sequence"});
  seq.only_keys({"files", "first", "count", "frame_time"});
  const long long first = seq.integer_or("first", 1), count = seq.at("count").integer();
  if (count < 1 || count > 1'000'000) seq.at("count").fail("must be between 1 and 1,000,000");
  if (first < 0 || first > 1'000'000'000) seq.at("first").fail("must be between 0 and 1,000,000,000");
  const double dt = seq.positive_or("frame_time", frame_time);
  const JsonValue files = seq.at("files");
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
  if (!s.repairs.empty()) o.notes.push_back(pattern + ": " + s.repairs);
  o.mesh = std::move(s.mesh);
  o.sequence = std::move(s.frames);
  o.sequence_frame_time = dt;
}

// The placed positions (the sequence's frames too) and the centroid the rigid motion turns about.
void place(const JsonValue& j, ObstacleSpec& o) {
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
}

}  // namespace

ObstacleSpec parse_obstacle(const JsonValue& j, const std::string& scene_path, double frame_time, double shot, BodyMeshCache& bodies) {
  j.only_keys({"name", "group", "mesh", "character", "transform", "motion"});
  ObstacleSpec o;
  o.name = j.at("name").string();
  o.group = j.string_or("group", "");
  if (j.has("mesh") == j.has("character")) j.fail("an obstacle needs exactly one of \"mesh\" and \"character\"");
  if (auto c = j.find("character")) read_character(j, *c, scene_path, shot, bodies, o);
  else if (auto seq = j.at("mesh").is_string() ? std::nullopt : j.at("mesh").find("sequence"))
    read_sequence(j.at("mesh"), *seq, scene_path, frame_time, o);
  else o.mesh = parse_mesh(j.at("mesh"), scene_path, false, nullptr, &o.notes);
  place(j, o);
  if (auto m = j.find("motion")) {
    m->only_keys({"translate", "rotate"});
    if (auto tr = m->find("translate")) o.translate = parse_track(*tr, "offset");
    if (auto ro = m->find("rotate")) o.rotate = parse_track(*ro, "degrees");
  }
  return o;
}

}  // namespace vdc
