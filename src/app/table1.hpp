// `vdcloth bench table1`: Koh et al. 2014's Table 1 (its three shots, each non-adaptive,
// adaptive and view-dependent) on the project's own scenes. Each run is a child `vdcloth run`
// process, so that its peak memory is its own and a failed run does not end the others.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

// The statistics of one run's stats.csv: faces, vertices and seconds per frame.
struct RunTable {
  int frames = 0;
  int faces_min = 0, faces_max = 0, vertices_min = 0, vertices_max = 0;
  double faces_mean = 0, vertices_mean = 0;
  double seconds_min = 0, seconds_max = 0, seconds_mean = 0;
  std::vector<int> faces;          // per frame
  std::vector<double> seconds;     // per frame
};

// Reads DIR/stats.csv (the columns frame, faces, vertices, seconds first). Throws InputError.
RunTable read_run_table(const std::string& stats_csv);

// Speed-up of `run` over `base`: base's mean seconds per frame over run's, both over the frames
// both have (the first min(frames) of each), which is how a baseline run made over the shot's
// first frames only compares. 0 when either has no frame; *shared gets the frame count.
double speedup_over_shared_frames(const RunTable& base, const RunTable& run, int* shared = nullptr);

// args: the options after `bench table1`. Returns the exit status: 0 when every run finished,
// 3 when one failed (the table says which), 2 on bad usage or scenes.
int table1_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace vdc
