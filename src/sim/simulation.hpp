// Runs a scene frame by frame: substeps of the implicit integrator, handles driving their nodes,
// and recovery from a failed step by halving it (logged), so a hard frame never ends a run.
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "physics/cloth_model.hpp"
#include "collision/collider.hpp"
#include "collision/untangle.hpp"
#include "physics/integrator.hpp"
#include "remesh/remesher.hpp"
#include "remesh/sizing.hpp"
#include "scene/scene.hpp"
#include "sim/step_recovery.hpp"
#include "view/depth_cache.hpp"

namespace vdc {

class ViewSizing;

enum class SimMode { Fixed, Adaptive, View };

bool parse_sim_mode(const std::string& name, SimMode& mode);
const char* sim_mode_name(SimMode mode);

struct SimOptions {
  SimMode mode = SimMode::Fixed;
  int threads = 1;
};

struct EnergyReport {
  double kinetic = 0, gravitational = 0, elastic = 0;
  double total() const { return kinetic + gravitational + elastic; }
};

struct FrameStats {
  int frame = 0;
  int faces = 0, vertices = 0;  // vertices: world-space nodes
  double seconds = 0;           // wall time of the frame
  int substeps = 0;             // steps taken, halvings included
  int halvings = 0;             // failed steps retried at half size
  int solver_iterations = 0;
  int factorizations = 0;
  double assemble_seconds = 0, solve_seconds = 0;
  double remesh_seconds = 0;  // sizing, remeshing and rebuilding the system (adaptive mode)
  int splits = 0, flips = 0, collapses = 0;
  int remesh_refused = 0;  // flips and collapses refused because they would make cloth cross cloth
  int proximities = 0;  // most proximity pairs in one step of the frame
  int untangle_moves = 0;  // vertex moves of untangling (after remeshing)
  int remesh_undone = 0;   // 1: remeshing made crossings untangling could not remove, so the
                           // frame kept the mesh it started with
  // View mode: faces at the frame's start by how the camera sees them, and the time taken by
  // the view factors (part of remesh_seconds).
  int visible_faces = 0, back_facing_faces = 0, out_of_frame_faces = 0;
  int defocused_faces = 0, blurred_faces = 0;  // visible, their screen-space floor set by the lens's blur
  int hidden_faces = 0;  // facing the camera in frame, behind something opaque (view.occlusion)
  // View mode with view.far_remesh_every above 1: 1 when no camera resolves the group's cloth
  // (level_of_detail.hpp), so that it is remeshed only on every far_remesh_every-th frame (the
  // view's counts above are then 0 on the frames between); summed over groups, how many.
  int far_groups = 0;
  double view_seconds = 0;
  int impacts = 0, collision_iterations = 0, collision_fallbacks = 0;
  int velocity_clamps = 0;  // steps whose velocity changes were clamped as a last resort
  long long collision_candidates = 0;  // most candidate pairs met in one detection round
  double collision_seconds = 0;
  EnergyReport energy;
};

// Where a stopped simulation resumes: the frame it had reached and its garments' meshes then,
// in the scene's garment order (a checkpoint, io/checkpoint.hpp).
struct ResumePoint {
  int frame = 0;
  std::vector<std::string> names;  // of the garments, to check against the scene
  std::vector<Mesh> garments;
};

class Simulation {
 public:
  using Log = std::function<void(const std::string&)>;
  // Starts at the scene's start: frame -preroll_frames (the frames before 0 are its pre-roll).
  Simulation(Scene scene, const SimOptions& options, Log log = {});
  // Resumes at `from`: the scene's garments take its meshes, and nothing is remeshed or
  // untangled, so the next frame is the one the stopped simulation would have made after
  // restart_solvers(). Throws InputError naming `source` when the meshes do not fit the scene.
  Simulation(Scene scene, const SimOptions& options, Log log, ResumePoint from, const std::string& source);

  // Simulates the next frame. Throws SimulationError when a step fails even at the smallest size.
  FrameStats step_frame();

  // Drops what the linear solver carries from step to step (the preconditioner's factorization,
  // the last velocity change as a first guess): the next frame starts it afresh from the meshes,
  // as a simulation resumed from this frame does. The collision hierarchies are kept: nothing
  // the collider finds depends on them. With a direct solver nothing dropped changes a result.
  void restart_solvers() { restart_pending_ = true; }
  // Shares the bodies' depth images (view.occlusion) with the scene's other garment groups,
  // stepped side by side at the same times.
  void share_depth_cache(std::shared_ptr<DepthCache> cache) { depth_cache_ = std::move(cache); }

  int frame() const { return frame_; }
  double time() const { return frame_ * scene_.frame_time; }
  // The scene as read: never changed by the run (its garment meshes are the start's).
  const Scene& scene() const { return scene_; }
  // The run's state: garment g's mesh now (positions, velocities, remeshed connectivity) and
  // obstacle o's mesh placed at time(), in the scene's order.
  const Mesh& garment_mesh(std::size_t g) const { return garments_[g]; }
  const Mesh& obstacle_mesh(std::size_t o) const { return obstacles_[o]; }
  const SimOptions& options() const { return options_; }
  EnergyReport energy() const;
  int num_faces() const;
  int num_nodes() const;  // cloth nodes (a seam's two sides share one): stats.csv's `vertices`

 private:
  void rebuild();                       // elements, assembler and solver from the meshes
  // The membranes' resistance to gathering beyond what coarse faces were made with: the view
  // block's in view mode, none otherwise.
  double gathering() const { return options_.mode == SimMode::View ? scene_.view.gathering : 0.0; }
  // Adaptive and view modes: sizing field and remesh, every frame (in view mode a far group's
  // every far_remesh_every-th frame).
  void remesh_garments(FrameStats& stats);
  // View mode: whether every garment of the group is beyond what the cameras resolve now (the
  // far level of detail, view.far_remesh_every); false while the drape settles and before
  // view.far_after.
  bool beyond_resolution_now() const;
  // Sizes and remeshes every garment, keeping each as sized, before its remesh, in
  // `started_with` (one slot a garment): the fallback goes on with this frame's factors. No flip
  // or collapse makes a garment cross the obstacles or another garment as they were `standing`.
  // What may hide cloth from camera `camera` (an index of scene().cameras).
  OccluderDrawing occluders_at(const std::vector<CollisionMesh>& garment_meshes, const std::vector<std::vector<Vec3>>& garment_x,
                               int camera) const;
  std::vector<RemeshStats> size_and_remesh(const std::vector<std::unique_ptr<ViewSizing>>& views,
                                           const std::vector<std::vector<ObstaclePlane>>& planes,
                                           const StandingSurfaces& standing, std::vector<Mesh>& started_with);
  // Removes interpenetrations of x_ at the current time (the steps' working vectors).
  UntangleReport untangle_cloth(FrameStats& stats);
  // The same on the garments' meshes (start-up, after remeshing): gathered, untangled, scattered.
  UntangleReport untangle_garments(FrameStats& stats);
  // After untangling at the start left crossings: logs, once, each garment that still crosses an
  // obstacle, with the obstacle and the count of crossing face pairs.
  void report_start_crossings();
  // After a remesh whose crossings untangling could not all remove (remeshed_pairs left): goes on
  // with whichever of the frame's start meshes and the remeshed ones has fewer.
  void keep_fewer_crossings(std::vector<Mesh> started_with, int remeshed_pairs, FrameStats& stats);
  void check_options_and_collect_obstacles();  // both constructors' first step
  void place_obstacles();               // moving obstacles' meshes at time()
  // Every obstacle's vertex positions at time t. The last two times asked for are remembered:
  // each step starts at the time the one before ended, and skinning a body is not free.
  std::vector<std::vector<Vec3>> obstacle_positions(double t);
  void gather(Eigen::VectorXd& x, Eigen::VectorXd& v) const;  // garments_ -> x, v in model order
  void gather_state() { gather(x_, v_); }
  void scatter_state();                 // x_, v_ -> garments_
  std::vector<VelocityConstraint> constraints(double t_end, double h) const;
  // One substep from time t to t_end, halved as step_recovery.hpp's policy says.
  void advance(double t, double t_end, FrameStats& stats);
  // Takes `step` (true), or says why it must be halved (false, `refused`); throws SimulationError
  // when the smallest step fails.
  bool take_step(const StepInterval& step, const StepRecoveryLimits& limits, FrameStats& stats, StepReport& refused);
  // Obstacle vertex positions at the start and end of a step, per obstacle.
  struct ObstacleMotion {
    std::vector<std::vector<Vec3>> start, end;
  };
  // Repulsion and friction terms of the proximity pairs at the start of a step.
  std::vector<ContactTerm> proximity_contacts(const std::vector<char>& fixed, const ObstacleMotion& obstacles, double h,
                                              FrameStats& stats);
  // Continuous collision handling of the step that just moved x_ from x_start; velocities follow.
  // Returns what the collider did: zones that did not separate (counted as fallbacks when
  // `last_resort`), or a detection over its work bound.
  CollisionStats resolve_collisions(const Eigen::VectorXd& x_start, double h, const std::vector<char>& fixed, const ObstacleMotion& obstacles,
                         FrameStats& stats, bool last_resort);
  // Halvings a step may take to let impact zones separate before the zones are frozen: four (a
  // sixteenth of a substep). A zero-thickness blade swinging at 3 m/s through a fold of cloth
  // needed three; frozen after two, the zones crossed the cloth over itself (bench/RESULTS.md,
  // issue 72's test files).
  static constexpr int kCollisionHalvings = 4;


  const Scene scene_;
  SimOptions options_;
  Log log_;
  int frame_ = 0;
  bool restart_pending_ = false;
  ClothModel model_;
  std::vector<int32_t> offsets_;  // first model node of each garment
  std::unique_ptr<ImplicitIntegrator> integrator_;
  // The state between frames: the garments' meshes, which the step loop's x_, v_ are gathered
  // from when its steps begin and scattered back to when they end.
  std::vector<Mesh> garments_;
  std::vector<Mesh> obstacles_;  // placed at time()
  std::vector<CollisionMesh> obstacle_faces_;  // the obstacles' faces, for collisions and sizing
  // Depth images of the bodies (view.occlusion), shared with the other garment groups of the
  // scene when stepped in an Ensemble.
  std::shared_ptr<DepthCache> depth_cache_ = std::make_shared<DepthCache>();
  struct ObstaclePositions {
    double t = 0;
    std::vector<std::vector<Vec3>> x;  // empty: not computed yet
  };
  std::array<ObstaclePositions, 2> obstacle_positions_;  // the most recent first
  std::unique_ptr<Collider> collider_;
  // The step loop's working vectors (all garments' nodes, model order): meaningful from a
  // gather_state() to the scatter_state() that ends the steps or the untangling using them.
  Eigen::VectorXd x_, v_;
};

}  // namespace vdc
