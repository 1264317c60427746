// A scene run as independent simulations, one per garment group (split_groups), stepped in
// parallel: a crowd whose characters each wear their own garments, as in Koh et al. 2014's
// ten-dancer shot, costs the sum of its members and uses every core. A process of a run made by
// several (vdcloth run under mpirun) steps only some of the groups: the others' scenes wait
// here until a group is handed over (adopt, drop).
#pragma once
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace vdc {

// One group's frame: its statistics and how long it took.
struct PartFrame {
  int group = 0;
  FrameStats stats;
  double seconds = 0;
};

class Ensemble {
 public:
  // The groups `here` are stepped here (split_groups' order, increasing; possibly none), every
  // group without it. options.threads is shared out: parts run side by side, each with
  // threads / parts (at least 1).
  Ensemble(Scene scene, const SimOptions& options, Simulation::Log log = {}, std::optional<std::vector<int>> here = std::nullopt);
  // Resumes the parts here at their ResumePoints (one a group of the whole scene, in group
  // order); `source` names where they came from in errors.
  Ensemble(Scene scene, const SimOptions& options, Simulation::Log log, std::vector<ResumePoint> from, const std::string& source,
           std::optional<std::vector<int>> here = std::nullopt);

  // Every part here one frame, the parts that took longest last frame first, in group order.
  // Throws the first part's SimulationError (in group order).
  std::vector<PartFrame> step_parts();
  // step_parts summed: counts, faces and part timings added in group order (accumulate);
  // `seconds` is the wall time of the whole frame.
  FrameStats step_frame();

  void restart_solvers();  // every part's (Simulation::restart_solvers)
  // Whether a restart can change what a group does next: the scene's linear solver carries
  // state from step to step that changes its results (an iterative one). Without it, a group
  // may be restarted, and so moved, after any frame.
  bool restart_changes_results() const;

  // Hands group g over: its simulation ends here, its scene waits (g must be here).
  void drop(int group);
  // Takes group g on, resumed at `from` (g must not be here); `source` names it in errors.
  void adopt(int group, ResumePoint from, const std::string& source);

  // The parts stepped here, in group order; parts()[k] simulates group here()[k].
  const std::vector<std::unique_ptr<Simulation>>& parts() const { return parts_; }
  const std::vector<int>& here() const { return here_; }
  const Simulation& part(int group) const;  // group's simulation (it must be here)
  int groups() const { return static_cast<int>(waiting_.size()); }  // of the whole scene
  const Scene& group_scene(int group) const;  // any group's, here or waiting
  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  const SimOptions& options() const { return options_; }
  int frame() const { return frame_; }
  int num_faces() const;  // of the parts here
  int num_nodes() const;  // cloth nodes (a seam's two sides share one): stats.csv's `vertices`

 private:
  // Splits the scene into its groups and builds those here in parallel, each by make(group,
  // its scene, its options, its log); with expected_groups > 0, throws InputError naming
  // `source` unless the scene has that many.
  template <class Make>
  void make_parts(Scene scene, std::optional<std::vector<int>> here, std::size_t expected_groups, const std::string& source, Make&& make);
  Simulation::Log part_log(int group) const;
  SimOptions part_options() const;

  std::string name_, path_;
  SimOptions options_;
  int frame_ = 0;  // of every group, here or waiting
  std::shared_ptr<std::mutex> log_mutex_ = std::make_shared<std::mutex>();
  Simulation::Log log_;
  std::vector<std::string> labels_;  // each group's prefix in the log ("<group>: "; none for one group)
  std::vector<int> here_;
  std::vector<std::unique_ptr<Simulation>> parts_;
  std::vector<std::unique_ptr<Scene>> waiting_;  // a group's scene while it is not here, else null
  int team_ = 1;  // threads stepping parts side by side
  int part_threads_ = 1;
  std::vector<double> part_seconds_;  // each part's wall time in the last frame: the order parts start in
  std::shared_ptr<DepthCache> bodies_ = std::make_shared<DepthCache>();  // the same for every group
};

// Adds one part's frame to a frame of the whole (everything but frame and seconds).
void accumulate(FrameStats& total, const FrameStats& part);
// The frame of the whole from its parts' (in group order): accumulated, `seconds` left 0.
FrameStats total_of(const std::vector<PartFrame>& parts);

}  // namespace vdc
