// How a run's failures travel: an exception as the exit status and line `vdcloth run` gives,
// and a stage run on every process of a cluster that learns whether all of them went through.
#pragma once
#include <exception>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/binary_io.hpp"
#include "dist/cluster.hpp"
#include "app/cli.hpp"

namespace vdc {

// What failed, as run_cli says it: the exit status and the line after "vdcloth: ".
struct Failure {
  int status = kExitOk;
  std::string what, why;  // what: "simulation failed", ...; empty for bad input
  std::string line() const { return what.empty() ? why : what + ": " + why; }
};

Failure failure_of(std::exception_ptr error);

// Runs `step` on every process of `cluster` and says whether all of them went through. One
// process: its exception goes on as it is. Several: each learns the others' outcome; when one
// failed, rank 0 says the first failure (with its rank) and every process returns its status.
template <class Step>
std::optional<int> together(const Cluster& cluster, std::ostream& err, Step&& step) {
  if (cluster.size() == 1) {
    step();
    return std::nullopt;
  }
  Failure mine;
  try {
    step();
  } catch (...) {
    mine = failure_of(std::current_exception());
  }
  BinaryWriter said;
  said.value<int32_t>(mine.status);
  said.string(mine.line());
  const std::vector<std::string> all = cluster.all_gather(said.bytes());
  for (std::size_t r = 0; r < all.size(); ++r) {
    BinaryReader in(all[r].data(), all[r].size());
    const int status = in.value<int32_t>();
    if (status == kExitOk) continue;
    const std::string line = in.string();
    if (cluster.root()) err << "vdcloth: " << (r > 0 ? "process " + std::to_string(r) + ": " : "") << line << std::endl;
    return status;
  }
  return std::nullopt;
}

}  // namespace vdc
