// The processes one run is made by: a single one when vdcloth is started on its own; the
// processes an MPI launcher started (`mpirun -np N vdcloth run ...`, Open MPI) otherwise, each
// with its rank, exchanging bytes. Only the thread that joined calls it.
#pragma once
#include <string>
#include <vector>

namespace vdc {

class Cluster {
 public:
  // Joins the launcher's processes (MPI_Init) when an MPI launcher started this one, which it
  // says in the environment (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK); otherwise a cluster
  // of one that needs no MPI at all. Throws std::runtime_error when MPI cannot start.
  Cluster();
  ~Cluster();  // MPI_Finalize
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Every process's bytes at rank 0, in rank order (elsewhere: none).
  std::vector<std::string> gather(const std::string& bytes) const;
  // Every process's bytes at every process, in rank order.
  std::vector<std::string> all_gather(const std::string& bytes) const;
  // Rank 0's bytes at every process (what the others pass is ignored).
  std::string broadcast(const std::string& bytes) const;
  void send(int to, const std::string& bytes) const;
  std::string receive(int from) const;
  // Ends every process of the run at once with `status` (MPI_Abort): for a process that cannot
  // go on while the others wait for it.
  [[noreturn]] void abort(int status) const;

 private:
  bool mpi_ = false;
  int rank_ = 0, size_ = 1;
};

// Whether an MPI launcher started this process (see Cluster()).
bool started_by_mpi_launcher();

}  // namespace vdc
