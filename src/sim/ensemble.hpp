// A scene run as independent simulations, one per garment group (split_groups), stepped in
// parallel: a crowd whose characters each wear their own garments, as in Koh et al. 2014's
// ten-dancer shot, costs the sum of its members and uses every core.
#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace vdc {

class Ensemble {
 public:
  // options.threads is shared out: parts run side by side, each with threads / parts (at least 1).
  Ensemble(Scene scene, const SimOptions& options, Simulation::Log log = {});
  // Resumes every part at its ResumePoint (one a part, in part order); `source` names where
  // they came from in errors.
  Ensemble(Scene scene, const SimOptions& options, Simulation::Log log, std::vector<ResumePoint> from, const std::string& source);

  // Every part one frame, the parts that took longest last frame first. Counts, faces and part
  // timings are summed over the parts; `seconds` is the wall time of the whole frame. Throws the
  // first part's SimulationError (in part order).
  FrameStats step_frame();

  void restart_solvers();  // every part's (Simulation::restart_solvers)

  const std::vector<std::unique_ptr<Simulation>>& parts() const { return parts_; }
  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  const SimOptions& options() const { return options_; }
  int frame() const { return parts_.front()->frame(); }
  int num_faces() const;
  int num_nodes() const;  // cloth nodes (a seam's two sides share one): stats.csv's `vertices`

 private:
  // Splits the scene into its parts and builds them in parallel, each by make(k, its scene, its
  // options, its log); with expected_parts > 0, throws InputError naming `source` unless the
  // scene has that many.
  template <class Make>
  void make_parts(Scene scene, std::size_t expected_parts, const std::string& source, Make&& make);

  std::string name_, path_;
  SimOptions options_;
  std::mutex log_mutex_;
  Simulation::Log log_;
  std::vector<std::unique_ptr<Simulation>> parts_;
  int team_ = 1;  // threads stepping parts side by side
  std::vector<double> part_seconds_;  // each part's wall time in the last frame: the order parts start in
};

// Adds one part's frame to a frame of the whole (everything but frame and seconds).
void accumulate(FrameStats& total, const FrameStats& part);

}  // namespace vdc
