// One implicit step on uniform sheets: assembly and linear solve measured separately, for each
// linear solver (the solve from 288 to 32k faces, the rest at about 2k, 8k and 32k faces).
// Run: build/bench/vdcloth_bench
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "core/mesh_build.hpp"
#include "physics/cloth_model.hpp"
#include "physics/integrator.hpp"
#include "physics/material.hpp"

namespace vdc {
namespace {

// A sheet of cells x cells squares (2 cells^2 faces), cotton, with a wavy deformation so that
// bending and membrane terms are all active, and a non-zero velocity field.
struct SheetProblem {
  ClothModel model;
  Eigen::VectorXd x, v;
  StepParams params;
  std::vector<VelocityConstraint> pins;

  explicit SheetProblem(int cells, int threads) {
    Mesh mesh = build_mesh(make_grid(1.0, 1.0, cells, cells));
    Material cotton;  // defaults are the cotton preset's order of magnitude
    append_garment(model, mesh, cotton);
    x.resize(3 * model.num_nodes);
    v.resize(3 * model.num_nodes);
    for (NodeId n : mesh.nodes()) {
      Vec3 p = mesh.x(n);
      p.y() = 0.02 * std::sin(12.0 * p.x()) * std::cos(9.0 * p.z());
      x.segment<3>(3 * n.idx) = 1.01 * p;
      v.segment<3>(3 * n.idx) = Vec3(0.0, 0.1 * std::sin(7.0 * p.x()), 0.0);
    }
    params.h = 0.005;
    params.drag = 0.1;
    params.threads = threads;
    v.segment<3>(0).setZero();
    v.segment<3>(3 * cells).setZero();
    pins = {{0, Vec3::Zero()}, {cells, Vec3::Zero()}};
  }
};

void BM_Assemble(benchmark::State& state) {
  SheetProblem p(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  SystemAssembler assembler(p.model);
  for (auto _ : state) {
    assembler.assemble(p.x, p.v, p.params);
    assembler.constrain(p.pins);
    benchmark::DoNotOptimize(assembler.rhs().data());
  }
  state.counters["faces"] = static_cast<double>(p.model.face_nodes.size());
}

void BM_Solve(benchmark::State& state) {
  SheetProblem p(static_cast<int>(state.range(0)), 2);
  auto kind = static_cast<LinearSolverKind>(state.range(1));
  SystemAssembler assembler(p.model);
  assembler.assemble(p.x, p.v, p.params);
  assembler.constrain(p.pins);
  auto solver = make_linear_solver(kind);
  solver->analyze(assembler.matrix());
  Eigen::VectorXd dv = Eigen::VectorXd::Zero(p.x.size());
  int iterations = 0;
  for (auto _ : state) {
    dv.setZero();
    SolveReport r = solver->solve(assembler.matrix(), assembler.rhs(), dv);
    iterations = r.iterations;
    if (!r.ok) state.SkipWithError("solve failed");
  }
  state.counters["faces"] = static_cast<double>(p.model.face_nodes.size());
  state.counters["iterations"] = iterations;
  state.SetLabel(linear_solver_name(kind));
}

// Consecutive steps of a sheet swinging from two pinned corners: the state moves on between
// iterations, as in a run, so a solver that reuses its factorization is measured fairly.
void BM_Step(benchmark::State& state) {
  SheetProblem p(static_cast<int>(state.range(0)), static_cast<int>(state.range(2)));
  auto kind = static_cast<LinearSolverKind>(state.range(1));
  LinearSolverParams solver_params;
  solver_params.threads = p.params.threads;
  ImplicitIntegrator integrator(p.model, kind, solver_params);
  Eigen::VectorXd x = p.x, v = p.v;
  double assemble = 0, solve = 0, iterations = 0, factorizations = 0;
  for (auto _ : state) {
    StepReport r = integrator.step(x, v, p.pins, p.params, 1e9);
    if (!r.ok) state.SkipWithError(r.failure.c_str());
    assemble += r.assemble_seconds;
    solve += r.solve_seconds;
    iterations += r.solver_iterations;
    factorizations += r.factorizations;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["faces"] = static_cast<double>(p.model.face_nodes.size());
  state.counters["assemble_ms"] = 1e3 * assemble / n;
  state.counters["solve_ms"] = 1e3 * solve / n;
  state.counters["iterations"] = iterations / n;
  state.counters["factorizations"] = factorizations / n;
  state.SetLabel(linear_solver_name(kind));
}

// Sheets: 32^2*2 = 2048, 64^2*2 = 8192, 128^2*2 = 32768 faces.
BENCHMARK(BM_Assemble)->ArgsProduct({{32, 64, 128}, {1, 2}})->Unit(benchmark::kMillisecond);
// Solvers: 0 cholmod-pcg, 1 cholmod, 2 ldlt, 3 cg (Jacobi). A lone solve of one matrix (direct
// solvers factor it; cholmod-pcg too, being without a factor yet).
BENCHMARK(BM_Solve)->ArgsProduct({{12, 24, 32, 64, 96, 128}, {1, 2, 3}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Step)->ArgsProduct({{32, 64, 128}, {0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace vdc
