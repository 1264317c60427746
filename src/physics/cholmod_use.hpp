// How the solvers call CHOLMOD: its OpenMP loops and BLAS calls kept on the calling thread,
// METIS's orderings side by side, each thread drawing its own random numbers (one at a time where
// it cannot), nodes (3x3 blocks) ordered rather than unknowns.
#pragma once
#include <cstddef>
#include <mutex>
#include <vector>

#include <Eigen/Sparse>
#include <cholmod.h>
#include <omp.h>

namespace vdc {

// Runs f on the calling thread with CHOLMOD's own OpenMP loops and its BLAS calls made serial.
// Debian's CHOLMOD (SuiteSparse 5.12) opens a fixed 4-thread team for small loops of every
// supernode; on a 2-core machine the thread hand-offs cost more than the arithmetic (a 400
// MFlop factorization took 120 ms idle and seconds under load). Called from inside an active
// parallel region, with one active level allowed, those nested regions run on one thread.
// (Not by allowing no active level around f instead: Debian's OpenBLAS, the OpenMP build, then
// waits forever in sched_yield for a team member it never gets.)
template <class F>
void cholmod_serial(F&& f) {
  omp_set_max_active_levels(1);
  if (omp_get_active_level() > 0) {
    f();
    return;
  }
#pragma omp parallel num_threads(2)
  {
#pragma omp master
    f();
  }
}

// METIS draws from libc's random generator, reseeded at the start of every ordering; glibc
// keeps it process-wide, so two orderings at once (the halves of a garment, the parts of a
// crowd) would draw from each other's sequence and get orderings, and so rounding, that change
// from run to run. The program gives each thread its own generator (metis_random.cpp): then
// orderings run side by side. Where it could not, they run one at a time under metis_lock,
// which guards that library state and so is process-wide.
inline std::mutex& metis_lock() {
  static std::mutex lock;
  return lock;
}
// Whether METIS calls this program's per-thread rand and srand (metis_random.cpp).
bool metis_draws_per_thread();
// Holds metis_lock for one METIS call unless each thread draws from its own generator.
class MetisTurn {
 public:
  MetisTurn() {
    if (!metis_draws_per_thread()) lock_ = std::unique_lock<std::mutex>(metis_lock());
  }

 private:
  std::unique_lock<std::mutex> lock_;
};

// The node graph of a system's unknowns [start, start + size) (3 a node, nothing outside the
// range coupled to them), from each node's first column (the pattern is blockwise): node j's
// neighbours are rows[col_start[j] .. col_start[j + 1]), itself included.
void node_graph(const Eigen::SparseMatrix<double>& a, Eigen::Index start, Eigen::Index size, std::vector<int>& col_start,
                std::vector<int>& rows);

// A view of a node graph (columns' rows in `col_start` / `rows`, both triangles) as a CHOLMOD
// symmetric pattern; the vectors must outlive it.
cholmod_sparse node_graph_view(std::vector<int>& col_start, std::vector<int>& rows);

// METIS nested dissection of a node graph (columns' rows in `col_start` / `rows`, both
// triangles), in its MetisTurn: node_perm[k] is the k-th node eliminated. False if METIS fails.
bool metis_node_order(std::vector<int>& col_start, std::vector<int>& rows, std::vector<int>& node_perm, cholmod_common& common);

}  // namespace vdc
