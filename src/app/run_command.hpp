// `vdcloth run`: a scene simulated frame by frame into an output directory, by one process or
// by the processes of an MPI launcher sharing its garment groups (dist/).
#pragma once
#include <ostream>
#include <string>

#include "app/run_args.hpp"

namespace vdc {

// Runs it; returns the exit status (0 done, 3 failed part-way); throws UsageError and
// InputError for bad input before anything is written.
int run_command(const RunArgs& args, std::ostream& out, std::ostream& err, bool interactive);

}  // namespace vdc
