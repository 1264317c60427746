// The numeric supernodal Cholesky factorization of a CHOLMOD symbolic factor, done here instead
// of by cholmod_factorize: the left-looking supernodal algorithm (Ng and Peyton 1993, "Block
// sparse Cholesky algorithms on advanced uniprocessor computers"), with CHOLMOD's supernodes,
// update order and BLAS calls, so the factor holds the same bits. What it leaves out is the
// OpenMP region Debian's CHOLMOD opens around every small loop (three a supernode and two a
// descendant update, about 4,000 a cloth step): serial, each still costs libgomp a team and a
// futex call, 2.3 us on the 2-core VM, about a tenth of a character shot's time.
#pragma once
#include <cstddef>
#include <vector>

#include <cholmod.h>

#include "physics/assembly.hpp"

namespace vdc {

class SupernodalCholesky {
 public:
  // Readies `factor`, CHOLMOD's supernodal symbolic analysis of a's pattern (its lower triangle
  // read), for factorizations of matrices of that pattern: gives the factor numeric storage
  // and maps each entry of a's lower triangle to its place in the permuted factor. False, and
  // the factor left to cholmod_factorize, when it is not supernodal (or not of int indices) or
  // an entry falls outside its pattern.
  bool prepare(const SparseMatrix& a, cholmod_factor& factor, cholmod_common& common);
  // factor's values become L with L L^T = P a P^T for a's values (a of the prepared pattern).
  // False when a is not positive definite, with factor.minor the column where that showed.
  // Call inside cholmod_serial: the BLAS then runs on the calling thread, as inside CHOLMOD.
  bool factorize(const SparseMatrix& a, cholmod_factor& factor);
  bool prepared_for(const cholmod_factor& factor) const { return prepared_ == &factor; }

 private:
  struct Entry {
    std::size_t source;  // index in a's values
    std::size_t target;  // index in the factor's values
  };
  const cholmod_factor* prepared_ = nullptr;
  std::vector<Entry> entries_;           // by target
  std::vector<std::size_t> entry_start_;  // per supernode: its first entry
  std::vector<int> supernode_of_;  // per column of L
  // The left-looking loop's state: map_[row] is the row's place in the current supernode;
  // head_[s] lists (through next_) the supernodes still to update s, each from its row lpos_[d].
  std::vector<int> map_, relative_map_, head_, next_, lpos_;
  std::vector<double> update_;  // a descendant's update to the current supernode
};

}  // namespace vdc
