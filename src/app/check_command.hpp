// `vdcloth check`: the frame-end invariant of a run, checked on its written meshes. For every
// frame, each garment against itself, every other garment and every obstacle, by the exact
// triangle-triangle test.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

struct CheckSummary {
  int frames_checked = 0;
  int frames_with_crossings = 0;
};

// Checks every `every`-th frame of run_dir's meshes, lists crossings on `out`, and writes
// run_dir/check.csv (one row per crossing pair of meshes) and run_dir/check_status.txt
// ("frames_checked frames_with_crossings every"), each only once complete. Throws InputError
// when the run has no meshes or a mesh cannot be read.
CheckSummary check_run(const std::string& run_dir, int every, std::ostream& out);

// args: the options after `check`. Returns 0 when no frame has a crossing, 3 when one has
// (the crossings are listed), 2 on bad usage or input.
int check_command(const std::vector<std::string>& args, std::ostream& out);

}  // namespace vdc
