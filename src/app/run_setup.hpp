// The first stage of `vdcloth run`: every process reads the scene (and the checkpoint it
// resumes from), places the garment groups on the processes and builds the groups it starts
// with.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "app/run_args.hpp"
#include "core/resource_usage.hpp"
#include "dist/cluster.hpp"
#include "output/checkpoint.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

struct RunSetup {
  std::optional<Ensemble> sim;      // the groups this process steps
  std::optional<Checkpoint> resume; // the checkpoint the run goes on from
  Checkpoint progress;              // what each checkpoint of this run records besides the meshes
  std::string dir;                  // the output directory
  int frames = 0, threads = 1;
  double settle_frames = 0;  // view mode: frames from the shot's start left to the adaptive sizing
  bool nothing_to_do = false;  // resumed at its last frame, its summary written
  std::vector<int> owner;      // the process stepping each group
  double rebuild_seconds_per_face = 0;  // what building this process's groups took
  int segments = 1;            // processes the run has been made in, this one included
  ResourceUsage before;        // of the segments before this one
};

// Fills `setup` (built in place: the ensemble's parts keep their log). Throws UsageError and
// InputError for bad input, anything else for a failure of the build.
void set_up_run(const RunArgs& args, const Cluster& cluster, const Simulation::Log& log, RunSetup& setup);

// The checkpoint of the run in `dir` to resume, checked against the scene file, this build,
// the mode and the checkpoint interval: anything else would make another run than the one
// stopped.
Checkpoint checkpoint_to_resume(const RunArgs& args, const std::string& dir, uint64_t build_hash);

}  // namespace vdc
