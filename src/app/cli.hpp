// The vdcloth command line: argument parsing, progress and exit status (0 done, 2 bad input or
// usage, 3 a simulation failure that could not be recovered).
#pragma once
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vdc {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitSimulationFailed = 3;

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Worker threads a command accepts (--threads): more is not a machine this runs on, and asking
// the thread library for a hundred thousand ends the process.
inline constexpr int kMaxThreads = 256;

// The whole number of an option's value, from `lowest` to `highest`; UsageError naming the option
// and the range otherwise.
int parse_int_in(const std::string& option, const std::string& value, int lowest, int highest);
// The same from 1 to 1,000,000.
int parse_positive_int(const std::string& option, const std::string& value);
// The number of an option's value, from `lowest` to `highest`; UsageError naming the option and
// the range otherwise.
double parse_number(const std::string& option, const std::string& value, double lowest, double highest);

// A command's arguments read in order: next() gives the next one, value() the value of the
// option next() just gave (UsageError "OPTION needs a value" when the arguments end first).
class ArgumentReader {
 public:
  explicit ArgumentReader(const std::vector<std::string>& args, std::size_t first = 0) : args_(args), next_(first) {}
  bool done() const { return next_ >= args_.size(); }
  const std::string& next() { return args_[next_++]; }
  const std::string& value() {
    if (done()) throw UsageError(args_[next_ - 1] + " needs a value");
    return args_[next_++];
  }

 private:
  const std::vector<std::string>& args_;
  std::size_t next_;
};

// `interactive`: out is a terminal, so progress redraws one line instead of logging each frame.
int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool interactive);

}  // namespace vdc
