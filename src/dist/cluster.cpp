#include "dist/cluster.hpp"

#include <mpi.h>

#include <climits>
#include <cstdlib>
#include <stdexcept>

namespace vdc {

namespace {
void check(int code, const char* call) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

int count_of(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX)) throw std::runtime_error("MPI: a message of " + std::to_string(bytes) + " bytes is over 2 GiB");
  return static_cast<int>(bytes);
}

// Each process's bytes with their sizes, laid end to end at `to` (every rank or rank 0).
std::vector<std::string> collect(const std::string& bytes, int size, bool everywhere, bool here) {
  const int mine = count_of(bytes.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  if (everywhere) check(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  else check(MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = count_of(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  std::string all(here ? total : 0, '\0');
  if (everywhere)
    check(MPI_Allgatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD), "MPI_Allgatherv");
  else
    check(MPI_Gatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Gatherv");
  std::vector<std::string> each;
  if (!here) return each;
  for (std::size_t r = 0; r < counts.size(); ++r) each.push_back(all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(counts[r])));
  return each;
}
}  // namespace

bool started_by_mpi_launcher() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

Cluster::Cluster() : mpi_(started_by_mpi_launcher()) {
  if (!mpi_) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("MPI: this MPI library cannot be used from a threaded program");
  // Errors come back as codes (and exceptions here) rather than ending the process unexplained.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
}

Cluster::~Cluster() {
  if (mpi_) MPI_Finalize();
}

std::vector<std::string> Cluster::gather(const std::string& bytes) const {
  if (!mpi_) return {bytes};
  return collect(bytes, size_, false, root());
}

std::vector<std::string> Cluster::all_gather(const std::string& bytes) const {
  if (!mpi_) return {bytes};
  return collect(bytes, size_, true, true);
}

std::string Cluster::broadcast(const std::string& bytes) const {
  if (!mpi_) return bytes;
  unsigned long long n = bytes.size();
  check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = root() ? bytes : std::string(n, '\0');
  check(MPI_Bcast(out.data(), count_of(n), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
}

void Cluster::send(int to, const std::string& bytes) const {
  if (!mpi_) throw std::logic_error("Cluster::send in a cluster of one");
  check(MPI_Send(bytes.data(), count_of(bytes.size()), MPI_BYTE, to, 0, MPI_COMM_WORLD), "MPI_Send");
}

std::string Cluster::receive(int from) const {
  if (!mpi_) throw std::logic_error("Cluster::receive in a cluster of one");
  MPI_Status status;
  check(MPI_Probe(from, 0, MPI_COMM_WORLD, &status), "MPI_Probe");
  int n = 0;
  check(MPI_Get_count(&status, MPI_BYTE, &n), "MPI_Get_count");
  std::string bytes(static_cast<std::size_t>(n), '\0');
  check(MPI_Recv(bytes.data(), n, MPI_BYTE, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return bytes;
}

void Cluster::abort(int status) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, status);
  std::_Exit(status);
}

}  // namespace vdc
