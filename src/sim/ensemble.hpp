// A scene run as independent simulations, one per garment group (split_groups), stepped in
// parallel: a crowd whose characters each wear their own garments, as in the seed paper's
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

  // Every part one frame. Counts, faces and part timings are summed over the parts; `seconds`
  // is the wall time of the whole frame. Throws the first part's SimulationError.
  FrameStats step_frame();

  const std::vector<std::unique_ptr<Simulation>>& parts() const { return parts_; }
  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  const SimOptions& options() const { return options_; }
  int frame() const { return parts_.front()->frame(); }
  int num_faces() const;
  int num_vertices() const;

 private:
  std::string name_, path_;
  SimOptions options_;
  std::mutex log_mutex_;
  Simulation::Log log_;
  std::vector<std::unique_ptr<Simulation>> parts_;
  int team_ = 1;  // threads stepping parts side by side
};

// Adds one part's frame to a frame of the whole (everything but frame and seconds).
void accumulate(FrameStats& total, const FrameStats& part);

}  // namespace vdc
