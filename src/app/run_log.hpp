// What `vdcloth run` says while it runs: warnings to the error stream and to the run's log.txt
// (kept aside until the output directory is set up, since the run's setup may warn before it),
// and rank 0's progress lines, rewritten in place on a terminal.
#pragma once
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "output/run_output.hpp"
#include "sim/simulation.hpp"

namespace vdc {

class RunLog {
 public:
  RunLog(std::ostream& out, std::ostream& err, bool root, bool interactive)
      : out_(out), err_(err), root_(root), interactive_(interactive) {}
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  void warn(const std::string& msg);
  // A line on the error stream only (what ends the run, said before it ends).
  void error(const std::string& msg) { err_ << "vdcloth: " << msg << std::endl; }
  // The sink the simulation warns through (it must not outlive this log).
  Simulation::Log sink() { return [this](const std::string& msg) { warn(msg); }; }
  // From now on warnings go to `output`'s log too: `first` (if not empty), then those kept aside.
  void attach(RunOutput& output, const std::string& first);
  // Rank 0's out: what the run says besides warnings (the other processes' goes nowhere).
  std::ostream& say() { return root_ ? out_ : muted_; }
  // A line of progress: in place on a terminal, a line each otherwise.
  void progress(const std::string& line);
  // Ends a progress line left open on the terminal.
  void end_line();

 private:
  std::ostream& out_;
  std::ostream& err_;
  bool root_, interactive_;
  std::ostringstream muted_;
  bool line_open_ = false;
  RunOutput* output_ = nullptr;
  std::vector<std::string> early_;
};

}  // namespace vdc
