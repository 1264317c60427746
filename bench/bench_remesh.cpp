// The remeshing loop (Narain et al. 2012, section 4) on its own: a wavy sheet of cells x cells
// whose sizing field asks for 1.5 cm edges on one side and 40 cm on the other, turning with v,
// so that one remesh splits, flips and collapses by the thousand, guarded against a layer 4 mm
// under it as a garment is against its body.
// Run: build/bench/vdcloth_bench --benchmark_filter=Remesh
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/mesh_build.hpp"
#include "remesh/crossing_guard.hpp"
#include "remesh/remesher.hpp"

namespace vdc {
namespace {

Mesh graded_wavy_sheet(int cells) {
  MeshSource source = make_grid(1, 1, cells, cells);
  for (Vec3& p : source.positions) p.y() = 0.03 * std::sin(7 * p.x()) * std::cos(5 * p.z());
  Mesh mesh = build_mesh(source);
  auto& sizing = mesh.vert_attrs().add<Mat2>(kSizingAttr, Mat2::Identity());
  for (VertId v : mesh.verts()) {
    const Vec2 u = mesh.u(v);
    const double h = 0.015 + 0.385 * u.x(), angle = 1.5 * u.y();
    Mat2 rotation;
    rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    const Mat2 scale = Vec2(1 / (h * h), 1 / (4 * h * h)).asDiagonal();
    sizing[v] = rotation * scale * rotation.transpose();
  }
  return mesh;
}

// arg: cells.
void BM_Remesh(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  const RemeshOptions options;
  std::vector<Triangle> layer;
  {
    const Mesh below = graded_wavy_sheet(cells);
    for (FaceId f : below.faces()) {
      Triangle t{below.x(below.face_node(f, 0)), below.x(below.face_node(f, 1)), below.x(below.face_node(f, 2))};
      for (Vec3& p : t) p.y() -= 0.004;
      layer.push_back(t);
    }
  }
  const StandingSurfaces standing(layer, std::vector<int>(layer.size(), -1));
  RemeshStats stats;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh mesh = graded_wavy_sheet(cells);
    state.ResumeTiming();
    stats = remesh(mesh, options, &standing, 0);
    benchmark::DoNotOptimize(mesh.num_faces());
  }
  state.counters["splits"] = stats.splits;
  state.counters["flips"] = stats.flips;
  state.counters["collapses"] = stats.collapses;
}
BENCHMARK(BM_Remesh)->Arg(48)->Arg(96)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vdc
