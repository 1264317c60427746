// Sparse symmetric positive-definite solvers behind one interface: CHOLMOD supernodal Cholesky
// factored every solve, conjugate gradients preconditioned by a reused (lagged) CHOLMOD factor,
// Eigen's simplicial LDL^T, and conjugate gradients with a Jacobi preconditioner.
#pragma once
#include <memory>
#include <string>

#include "physics/assembly.hpp"

namespace vdc {

enum class LinearSolverKind { CholmodPcg, Cholmod, SimplicialLdlt, ConjugateGradient };

// Parses "cholmod-pcg", "cholmod", "ldlt" or "cg"; returns false for anything else.
bool parse_linear_solver_kind(const std::string& name, LinearSolverKind& kind);
const char* linear_solver_name(LinearSolverKind kind);
// Whether the solver carries from one solve to the next anything that changes its results (a
// first guess, a factorization kept as preconditioner): the iterative ones. A direct solver's
// result depends on the system alone, so it may be started afresh at any step.
bool carries_state(LinearSolverKind kind);

struct SolveReport {
  bool ok = false;
  int iterations = 0;      // CG iterations; 1 for a direct solve
  int factorizations = 0;  // Cholesky factorizations done by this solve
  double residual = 0;  // relative residual |A x - b| / |b|
};

struct LinearSolverParams {
  double cg_tolerance = 1e-6;  // relative residual for the iterative solvers
  int cg_max_iterations = 2000;  // Jacobi-preconditioned CG
  // cholmod-pcg: refactor when the preconditioned CG needed more than this many iterations, or
  // fall back to a fresh factorization when it has not converged within twice as many.
  int refactor_iterations = 6;
  int threads = 1;  // for the matrix-vector products of cholmod-pcg
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // Call once per sparsity pattern (after topology changes); values may be arbitrary.
  virtual void analyze(const SparseMatrix& a) = 0;
  // Solves a x = b; x holds the initial guess on entry (used by iterative solvers).
  virtual SolveReport solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
};

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const LinearSolverParams& params = {});

}  // namespace vdc
