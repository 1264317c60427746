// A Cholesky solve split in two across a vertex separator of the system's node graph (one
// level of George's 1973 nested dissection, the separator eliminated last): each half, its
// interior and the separator, is factored on its own (the two on two threads), and the
// separator's dense Schur complement joins them. With A ordered as [A00 0 A0S; 0 A11 A1S; AS0
// AS1 ASS], half h factors M_h = [Ahh AhS; ASh ASS] = L_h L_h^T, whose separator block gives
// L_hS L_hS^T = ASS - ASh Ahh^-1 AhS; then S = L_0S L_0S^T + L_1S L_1S^T - ASS is the Schur
// complement of the whole, x_S = S^-1 (b_S - g_0 - g_1) with g_h = ASh Ahh^-1 b_h from one
// forward substitution of each half, and each half's interior from one back substitution.
// A garment's system is one block the threads could not share; split, its two halves can.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "physics/linear_solver.hpp"

namespace vdc {

class SeparatedCholesky {
 public:
  SeparatedCholesky();
  ~SeparatedCholesky();
  SeparatedCholesky(const SeparatedCholesky&) = delete;
  SeparatedCholesky& operator=(const SeparatedCholesky&) = delete;

  // Splits the unknowns [start, start + size) of `a` (3 a node; nothing outside the range
  // couples to them) and analyzes both halves. False, and nothing to use, when the nodes do not
  // split into two halves of at least a fifth of them each with a separator of at most a tenth
  // of them and at most 3 sqrt(n) nodes.
  bool analyze(const SparseMatrix& a, Eigen::Index start, Eigen::Index size, int threads = 1);
  // Factors half h (0 or 1) with `a`'s current values (the pattern analyzed). The two halves may
  // be factored at once on two threads.
  bool factor_half(const SparseMatrix& a, int h);
  // After both halves are factored: x for b (the range's unknowns), with the relative residual.
  // The same as its steps one after another: forward_half for each half (each once its half is
  // factored: the two may run at once), solve_separator, back_half for each half (the two at
  // once), finish.
  SolveReport solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Half h's forward substitution of b with its separator's right-hand side 0: y_h = L_h^-1 b_h.
  bool forward_half(const Eigen::VectorXd& b, int h);
  // After both forward substitutions: the Schur complement's system for the separator's unknowns.
  bool solve_separator(const SparseMatrix& a, const Eigen::VectorXd& b);
  // Half h's back substitution with the separator's unknowns fixed: its interior's unknowns in x
  // (of the range's size; the two halves write different entries).
  bool back_half(int h, Eigen::VectorXd& x);
  // After both back substitutions: the separator's unknowns in x, and the relative residual.
  SolveReport finish(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

  Eigen::Index half_unknowns(int h) const;  // interior and separator
  Eigen::Index separator_unknowns() const { return static_cast<Eigen::Index>(separator_.size()); }

 private:
  struct Half;
  Eigen::Index start_ = 0, size_ = 0;
  std::array<std::unique_ptr<Half>, 2> halves_;
  std::vector<Eigen::Index> separator_;  // the separator's unknowns (range-relative), in order
  // Where each lower-triangle entry of ASS comes from: (row, column, index into a's values).
  struct Entry {
    int row, col;
    Eigen::Index source;
  };
  std::vector<Entry> separator_entries_;
  Eigen::VectorXd separator_x_;  // the separator's unknowns, from solve_separator
};

}  // namespace vdc
