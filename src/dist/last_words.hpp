// What a process of a run made by several says when it is stopped from outside: mpirun sends
// SIGTERM to the others when one of them dies (killed, out of memory), and a user may send
// SIGINT or SIGHUP. A thread waits for these signals, writes the summary and log line last left
// with it, says why on the error stream and ends the process with status 3.
#pragma once
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

namespace vdc {

class LastWords {
 public:
  // Blocks the signals in this thread and every thread it starts afterwards (so construct it
  // before MPI or OpenMP start theirs) and starts the waiting thread.
  LastWords();
  // What to write when stopped: `summary` (with "error" set to why) to `summary_path`, a line
  // to `log_path`, and `where` after the message on the error stream. Empty paths: nothing.
  void leave(const std::string& summary_path, nlohmann::json summary, const std::string& log_path, const std::string& where);

 private:
  struct Words;
  std::shared_ptr<Words> words_;
};

}  // namespace vdc
