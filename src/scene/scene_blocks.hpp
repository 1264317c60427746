// The scene file's blocks, each read by a file of its own named as its section of
// docs/scene-format.md: scene_air.cpp (`air`), scene_solver.cpp (`solver`), scene_remeshing.cpp
// (`remeshing`), scene_collision.cpp (`collision`), scene_mesh.cpp (a garment's or obstacle's
// `mesh`), scene_garments.cpp (`garments[i]` and `garments[i].handles[j]`), scene_fit.cpp (a
// garment's `fit`), scene_obstacles.cpp (`obstacles[i]`), scene_character.cpp
// (`obstacles[i].character`), scene_crowds.cpp (`crowds[i]`), scene_camera.cpp (`camera` and `cameras`),
// scene_view.cpp (`view`). scene.cpp reads the top level and puts the blocks together.
// Each throws InputError naming the file, the key path and the problem.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/surface_repair.hpp"
#include "io/json_reader.hpp"
#include "scene/body.hpp"
#include "scene/fitting.hpp"
#include "scene/scene.hpp"

namespace vdc {

AirSpec parse_air(const JsonValue& j);
SolverSpec parse_solver(const JsonValue& j);

// The `remeshing` block: the sizing's parameters and --mode fixed's edge size (0: none given).
struct RemeshingBlock {
  SizingParams sizing;
  double fixed_size = 0;
};
RemeshingBlock parse_remeshing(const JsonValue& j);
CollisionParams parse_collision(const JsonValue& j);

// A `mesh`: an OBJ file, a grid, or (garments only) a dress or tube pattern, or (obstacles only)
// a sphere. With `pattern`, a procedural garment's sizes are kept there. An obstacle's OBJ is
// repaired for collisions (core/surface_repair.hpp), what was found added to `notes`.
Mesh parse_mesh(const JsonValue& j, const std::string& scene_path, bool garment, std::optional<GarmentPattern>* pattern = nullptr,
                std::vector<std::string>* notes = nullptr);
// An obstacle's surface built as a mesh, repaired; a note naming `file` if it needed repairs.
ObstacleSurface obstacle_surface(const MeshSource& surface, const std::string& file, std::vector<std::string>* notes);

// What making a garment again for the figure wearing it needs (fit_worn_garments).
struct GarmentMaking {
  std::optional<GarmentPattern> pattern;  // a procedural garment's sizes on the project's figure, to make it again for another
  std::optional<Transform> transform;
  bool rest_initial = false;
};

// A `garments[i]` entry placed in the world as given, on the project's figure; its handles
// chosen on it (those attached to a joint are tied by attach_handles, once the obstacles are known).
GarmentSpec parse_garment(const JsonValue& j, const std::string& scene_path, GarmentMaking& making);
// Node n of a garment's mesh held by handle `index`, anchored where it is.
void hold_node(Mesh& mesh, NodeId n, int32_t index);
// The handles of `entries` with an `attach`, tied to their character's joint as at `start_time`.
void attach_handles(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments,
                    const std::vector<ObstacleSpec>& obstacles, double start_time);

// The procedural garments of the scene made again for the characters wearing them (each
// garment's `fit`), in the pose they are put on in; `shot` is the scene's length (s).
void fit_worn_garments(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments,
                       const std::vector<GarmentMaking>& making, const std::vector<ObstacleSpec>& obstacles, double start_time,
                       double shot, BodyMeshCache& bodies);

// An `obstacles[i]` entry; `shot` is the scene's length (s): a character's build looks at the
// poses it takes in the shot.
ObstacleSpec parse_obstacle(const JsonValue& j, const std::string& scene_path, double frame_time, double shot, BodyMeshCache& bodies);
// An obstacle's `character` block, placed by the obstacle's `transform` (if any); what reading
// its files found and repaired added to `notes`.
std::shared_ptr<const Character> parse_character(const JsonValue& c, const std::optional<JsonValue>& transform,
                                                 const std::string& scene_path, double shot, BodyMeshCache& bodies,
                                                 std::vector<std::string>& notes);

// The `camera` block or the `cameras` list of the top level `top` (none: no camera); a channel
// file named relative to `scene_path`, its frames `frame_time` apart.
std::vector<ShotCamera> parse_cameras(const JsonValue& top, const std::string& scene_path, double frame_time);
ViewParams parse_view(const JsonValue& j);

// What a character's arms keep from its body by default and from what its garments' handles
// hold (m; build_clearing_arms, GarmentFit::ease_clearing_arms), and how far apart in time the
// poses they are checked in are (s).
inline constexpr double kArmClearance = 0.01, kPoseSampleTime = 1.0 / 30;

}  // namespace vdc
