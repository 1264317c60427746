// The scene file's top level (docs/scene-format.md, "Scene"): its timing and settings, its
// blocks read by their own files (scene_blocks.hpp) and put together: the characters placed
// for the pre-roll, the garments fitted to their wearers, handles tied to joints. And the
// scene's parts by garment group.
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "scene/scene_blocks.hpp"
#include "scene/obj_sequence.hpp"
#include "scene/scene_crowds.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

// The name is the default output directory's (out/NAME): one path component, nothing else.
std::string scene_name(const JsonValue& j, const std::string& path) {
  const std::string name = j.string_or("name", fs::path(path).stem().string());
  const bool control = std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  if (name.empty() || name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos || control)
    (j.has("name") ? j.at("name") : j).fail("the scene's name must be one file name (no slashes, not . or ..): it names the output directory");
  return name;
}

// The keys of the top level but the garments, obstacles, crowds, camera and view.
void read_settings(const JsonValue& j, Scene& s) {
  s.frame_time = j.has("frame_time") ? j.at("frame_time").positive() : s.frame_time;
  const long long frames = j.integer_or("frames", s.frames);
  if (frames < 1 || frames > 10'000'000) j.at("frames").fail("must be between 1 and 10,000,000");
  s.frames = static_cast<int>(frames);
  long long sub = j.integer_or("substeps", s.substeps);
  if (sub < 1 || sub > 10000) j.at("substeps").fail("must be between 1 and 10000");
  s.substeps = static_cast<int>(sub);
  s.gravity = j.vec3_or("gravity", s.gravity);
  if (auto a = j.find("air")) s.air = parse_air(*a);
  if (auto so = j.find("solver")) s.solver = parse_solver(*so);
  if (auto r = j.find("remeshing")) {
    const RemeshingBlock block = parse_remeshing(*r);
    s.remeshing = block.sizing;
    s.fixed_size = block.fixed_size;
  }
  if (auto c = j.find("collision")) s.collision = parse_collision(*c);
}

// The run starts before the shot by the longest pre-roll, characters in their dressing poses.
void place_for_preroll(Scene& s) {
  double preroll = 0;
  for (const auto& o : s.obstacles)
    if (o.character) preroll = std::max(preroll, o.character->preroll());
  s.preroll_frames = static_cast<int>(std::ceil(preroll / s.frame_time - 1e-9));
  if (s.preroll_frames == 0) return;
  for (auto& o : s.obstacles)
    if (o.character) {
      const std::vector<Vec3> x = o.character->positions_at(s.start_time());
      for (NodeId n : o.mesh.nodes()) o.mesh.x(n) = x[static_cast<std::size_t>(n.idx)];
    }
}

void check_obstacle_groups(const Scene& s, const SceneEntries& entries) {
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const std::string& group = s.obstacles[k].group;
    if (!group.empty() && std::none_of(s.garments.begin(), s.garments.end(), [&](const GarmentSpec& g) { return g.group == group; }))
      entries.obstacles[k].at("group").fail("no garment is in group '" + group + "'");
  }
}

}  // namespace

Scene load_scene(const std::string& path) {
  JsonValue j = JsonValue::load_file(path);
  j.only_keys({"name", "frame_time", "frames", "substeps", "gravity", "air", "solver", "remeshing", "collision", "garments", "obstacles", "crowds", "camera",
               "cameras", "view"});
  Scene s;
  s.path = path;
  s.name = scene_name(j, path);
  read_settings(j, s);
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
  // Each garment made for the character wearing it, in its dressing pose; then the handles
  // attached to a character's joint, now that the obstacles are known.
  place_for_preroll(s);
  fit_worn_garments(entries.garments, s.garments, making, s.obstacles, s.start_time(), s.frames * s.frame_time, bodies);
  attach_handles(entries.garments, s.garments, s.obstacles, s.start_time());
  check_obstacle_groups(s, entries);
  s.cameras = parse_cameras(j, path, s.frame_time);
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

const ShotCamera* Scene::find_camera(const std::string& camera) const {
  if (camera.empty()) return cameras.empty() ? nullptr : &cameras.front();
  for (const ShotCamera& c : cameras)
    if (c.name == camera) return &c;
  return nullptr;
}

std::vector<const CameraPath*> Scene::camera_paths() const {
  std::vector<const CameraPath*> paths;
  for (const ShotCamera& c : cameras) paths.push_back(&c.path);
  return paths;
}

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
