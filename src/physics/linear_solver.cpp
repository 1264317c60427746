#include "physics/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

namespace vdc {

namespace {

double relative_residual(const SparseMatrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  double nb = b.norm();
  return nb > 0 ? (a * x - b).norm() / nb : (a * x).norm();
}

template <class Factorization>
class DirectSolver final : public LinearSolver {
 public:
  void analyze(const SparseMatrix& a) override { llt_.analyzePattern(a); }
  SolveReport solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    SolveReport r;
    llt_.factorize(a);
    if (llt_.info() != Eigen::Success) return r;
    x = llt_.solve(b);
    r.iterations = 1;
    r.residual = relative_residual(a, b, x);
    r.ok = llt_.info() == Eigen::Success && x.allFinite() && r.residual < 1e-6;
    return r;
  }

 private:
  Factorization llt_;
};

class CgSolver final : public LinearSolver {
 public:
  explicit CgSolver(const LinearSolverParams& p) {
    cg_.setTolerance(p.cg_tolerance);
    cg_.setMaxIterations(p.cg_max_iterations);
  }
  void analyze(const SparseMatrix&) override {}
  SolveReport solve(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    SolveReport r;
    cg_.compute(a);
    x = cg_.solveWithGuess(b, x);
    r.iterations = static_cast<int>(cg_.iterations());
    r.residual = cg_.error();
    r.ok = cg_.info() == Eigen::Success && x.allFinite();
    return r;
  }

 private:
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg_;
};

}  // namespace

bool parse_linear_solver_kind(const std::string& name, LinearSolverKind& kind) {
  if (name == "cholmod") kind = LinearSolverKind::Cholmod;
  else if (name == "ldlt") kind = LinearSolverKind::SimplicialLdlt;
  else if (name == "cg") kind = LinearSolverKind::ConjugateGradient;
  else return false;
  return true;
}

const char* linear_solver_name(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::Cholmod: return "cholmod";
    case LinearSolverKind::SimplicialLdlt: return "ldlt";
    case LinearSolverKind::ConjugateGradient: return "cg";
  }
  return "?";
}

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const LinearSolverParams& params) {
  switch (kind) {
    case LinearSolverKind::Cholmod:
      return std::make_unique<DirectSolver<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>>();
    case LinearSolverKind::SimplicialLdlt:
      return std::make_unique<DirectSolver<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>>>();
    case LinearSolverKind::ConjugateGradient:
      return std::make_unique<CgSolver>(params);
  }
  return nullptr;
}

}  // namespace vdc
