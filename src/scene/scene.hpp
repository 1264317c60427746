// A scene: garments (mesh, placement, material, handles), obstacles, gravity, air, timing and
// solver settings, read from JSON (format in docs/scene-format.md).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh.hpp"
#include "physics/assembly.hpp"
#include "physics/linear_solver.hpp"
#include "physics/material.hpp"
#include "collision/collider.hpp"
#include "remesh/sizing.hpp"
#include "scene/handle.hpp"
#include "core/track.hpp"
#include "scene/character.hpp"
#include "view/camera.hpp"
#include "view/view_factor.hpp"

namespace vdc {

struct GarmentSpec {
  std::string name;
  std::string group;  // garments of different groups never touch: they are simulated apart
  Mesh mesh;  // at the start, placed in world space; node attributes kHandleAttr and kAnchorAttr set
  Material material;
  std::vector<ClothHandle> handles;
  // A procedural garment made for the character wearing it (fitting.hpp): the character's name
  // (empty: made as given) and the share of its ease it keeps.
  std::string fitted_to;
  double ease = 1.0;
  bool sheer = false;  // see-through: hides nothing from the camera (view.occlusion)
};

// An obstacle: a mesh placed by its transform, then moved rigidly over time by its motion:
// x(t) = R(rotate(t)) (x_placed - pivot) + pivot + translate(t), pivot the placed centroid.
struct ObstacleSpec {
  std::string name;
  std::string group;  // collides with its group's garments only; empty: with every garment
  Mesh mesh;               // world positions at time 0 (a run's are Simulation::obstacle_mesh)
  std::vector<Vec3> rest;  // placed positions, by node index
  Vec3 pivot = Vec3::Zero();
  Vec3Track translate;     // offsets, m
  Vec3Track rotate;        // degrees about X, then Y, then Z
  // An OBJ sequence (placed by the transform): replaces `rest` as the positions before motion.
  std::vector<std::vector<Vec3>> sequence;
  double sequence_frame_time = 0;
  // An animated character (placed by its own transform): replaces `rest` likewise.
  std::shared_ptr<const Character> character;
  std::vector<std::string> notes;  // what reading its files found and repaired, for the run's log
  bool moves() const { return !translate.empty() || !rotate.empty() || sequence.size() > 1 || character; }
  std::vector<Vec3> positions_at(double t) const;
  // A ball that holds the obstacle at time t, found without placing its vertices: a character
  // that no rigid motion moves (Character::reach_at); radius -1 (unknown) otherwise.
  std::pair<Vec3, double> reach_at(double t) const;
};

struct AirSpec {
  double damping = 0.0;  // 1/s
  double drag = 0.0;     // N s/m^3
  Vec3 wind = Vec3::Zero();
};

struct SolverSpec {
  LinearSolverKind linear = LinearSolverKind::Cholmod;
  LinearSolverParams params;
  double max_velocity_change = 50.0;  // m/s in one step: beyond it the step is retried smaller
  int max_step_halvings = 8;
};

// A camera of the shot: the `camera` block (no name) or an entry of the `cameras` list (a stereo
// camera is two: its eyes).
struct ShotCamera {
  std::string name;  // empty for the `camera` block
  CameraPath path;
};

struct Scene {
  std::string path;  // the scene file
  std::string name;
  double frame_time = 0.04;  // s
  int frames = 250;
  int substeps = 8;
  Vec3 gravity = Vec3(0, -9.8, 0);
  AirSpec air;
  SolverSpec solver;
  SizingParams remeshing;  // the `remeshing` block
  CollisionParams collision;
  double fixed_size = 0;   // m: edge size of --mode fixed; 0 means remeshing.size_min
  std::vector<GarmentSpec> garments;
  std::vector<ObstacleSpec> obstacles;
  // Obstacles of other garment groups (a part of a crowd, split_groups and keep_groups): they
  // never touch this scene's garments but may hide them from the camera (view.occlusion). One
  // copy each, shared by the parts (a crowd of K would otherwise hold K - 1 copies a part).
  std::vector<std::shared_ptr<const ObstacleSpec>> hiding;
  std::vector<ShotCamera> cameras;  // the `camera` block or the `cameras` list; --mode view needs one
  ViewParams view;                   // the `view` block
  // Frames simulated before the shot's frame 0 (from time -preroll_frames * frame_time, never
  // written): the longest of the characters' pre-rolls, in whole frames. The garments' and
  // obstacles' meshes are placed at the start of it.
  int preroll_frames = 0;
  double start_time() const { return -preroll_frames * frame_time; }
  // The camera named `camera`, the first camera for an empty name; nullptr if there is none.
  const ShotCamera* find_camera(const std::string& camera = "") const;
  // The cameras' paths, in order.
  std::vector<const CameraPath*> camera_paths() const;
};

// Changes below any meaning a scene's author gives them (`vdcloth run --perturb` and
// `--perturb-resolution`): a run made with one differs from the unperturbed run only by how the
// change grows, the chaos floors `vdcloth fidelity --floor` measures against.
struct Perturbation {
  double gravity = 0;     // gravity times (1 + gravity)
  double resolution = 0;  // the remesher lets every edge be (1 + resolution) times as long
  bool operator==(const Perturbation&) const = default;
};
void apply_perturbation(Scene& scene, const Perturbation& p);

// Reads and checks a scene and everything it references. Throws InputError naming the file, the
// key path (e.g. garments[0].material) and the problem.
Scene load_scene(const std::string& path);

// The scene's independent parts, one per garment group in order of first appearance: each has
// its group's garments, its group's obstacles and the obstacles of no group (copied into every
// part), and the scene's settings. A scene without groups is one part.
std::vector<Scene> split_groups(Scene scene);
// The faces of each group's garments at the start, in split_groups' order: a first guess of
// what each part costs.
std::vector<double> group_faces(const Scene& scene);

// The scene cut down to the named garment groups: their garments, their obstacles and the
// obstacles of no group. Each group is simulated as it would be in the whole scene (its part of
// split_groups is the same), so one character of a crowd can be run, or a crowd run in shares.
// Throws std::invalid_argument naming a group the scene's garments do not have, and the ones
// they do.
Scene keep_groups(Scene scene, const std::vector<std::string>& groups);

}  // namespace vdc
