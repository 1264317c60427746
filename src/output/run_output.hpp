// What a run leaves in its output directory: frames/ (one OBJ per garment and obstacle per
// frame), stats.csv (one row a frame) and summary.json.
#pragma once
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/resource_usage.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

// The run's log: every warning the run gave, one line each, in order (also on the error stream).
inline constexpr const char* kLogFile = "log.txt";

// The mesh files of one written frame, by mesh name ("cloth_<garment>", "obstacle_<name>").
using FrameFiles = std::map<std::string, std::string>;

// Every frame a run wrote meshes for, by frame number. Throws InputError when RUN_DIR/frames is
// missing or holds no frame mesh.
std::map<int, FrameFiles> read_frame_files(const std::string& run_dir);

// A garment's size at the end of the run, as summary.json gives it.
struct GarmentSize {
  int faces = 0, vertices = 0;
};
// The sizes of one group's garments now, in its scene's order.
std::vector<GarmentSize> garment_sizes(const Simulation& part);

// Whether DIR/summary.json says the run is done with `frames` frames (a resume has nothing to do).
bool run_is_done(const std::string& dir, int frames);

class RunOutput {
 public:
  // Creates DIR and DIR/frames, removing frame files of an earlier run. Throws InputError if the
  // directory cannot be made.
  explicit RunOutput(const std::string& dir);
  // Goes on with the run in DIR from frame `resume_at`: keeps its stats rows and frame files up to
  // that frame and removes the later ones (made after its last checkpoint). Throws InputError
  // when DIR's stats.csv does not hold every frame up to `resume_at`.
  RunOutput(const std::string& dir, int resume_at);
  // One of the other processes of a run made by several: writes its groups' frames and log
  // lines into DIR, which the first process has set up, and no table.
  static RunOutput joining(const std::string& dir);
  // Meshes of every garment and obstacle of the groups stepped in `run` (the obstacles of no
  // group with group 0's).
  void write_frame(const Ensemble& run, int frame) const;
  void write_stats_row(const FrameStats& s);
  // Adds a line to DIR/log.txt (a new run starts it empty, a resumed one goes on with it); a
  // log that cannot be written does not stop the run (the error stream still has the line).
  void append_log(const std::string& line) const;
  // summary.json's contents. status: "done" or "failed"; error: message when failed. `sizes`:
  // each group's garment_sizes, every group of the scene in order (none yet: zeros); `usage` covers all
  // `segments` processes the run was made in; `perturbation`: what the scene was perturbed by.
  nlohmann::json summary(const Ensemble& run, const std::vector<std::vector<GarmentSize>>& sizes, const std::string& status, const std::string& error,
                         const ResourceUsage& usage, int segments, int frames_done, int threads, const Perturbation& perturbation) const;
  void write_summary(const nlohmann::json& summary) const;
  const std::string& dir() const { return dir_; }

 private:
  void tally(int faces, double seconds);  // one more row in the summary's statistics

  RunOutput() = default;

  std::string dir_;
  std::ofstream stats_;
  double max_seconds_ = 0, sum_seconds_ = 0;
  int min_faces_ = 0, max_faces_ = 0;
  double sum_faces_ = 0;
  int rows_ = 0;
};

}  // namespace vdc
