// Collision detection on a dressed character in motion: one proximity search and one
// continuous-detection round (the common case now: a step that meets no impact), on the solo
// dancer's dress after 20 frames of the scene, its body at that time and one step later.
// Run: build/bench/vdcloth_bench --benchmark_filter='Detection|Candidates'
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>
#include <set>

#include "collision/candidates.hpp"
#include "collision/collider.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {
namespace {

struct DressedCharacter {
  std::vector<std::array<int32_t, 3>> cloth_faces;
  Eigen::VectorXd x, v;
  std::vector<double> mass;
  std::vector<char> fixed;
  std::vector<std::vector<Vec3>> body_now, body_next, body_v;
  std::vector<CollisionMesh> body;
  int32_t num_nodes = 0;
  double band = 0, h = 0;
  CollisionParams params;
};

// The dress after 20 frames of solo-dancer (mode 1: adaptive, 2: view), made once per mode.
const DressedCharacter& dressed_character(int mode) {
  static std::map<int, std::unique_ptr<DressedCharacter>> made;
  auto& slot = made[mode];
  if (slot) return *slot;
  Simulation sim(load_scene(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/solo-dancer.json"),
                 SimOptions{mode == 1 ? SimMode::Adaptive : SimMode::View, 2});
  for (int f = 0; f < 20; ++f) sim.step_frame();
  auto d = std::make_unique<DressedCharacter>();
  const Scene& scene = sim.scene();
  const Mesh& dress = sim.garment_mesh(0);
  d->num_nodes = dress.node_capacity();
  d->x = Eigen::VectorXd::Zero(3 * d->num_nodes);
  d->v = Eigen::VectorXd::Zero(3 * d->num_nodes);
  for (NodeId n : dress.nodes()) {
    d->x.segment<3>(3 * n.idx) = dress.x(n);
    d->v.segment<3>(3 * n.idx) = dress.v(n);
  }
  for (FaceId f : dress.faces()) d->cloth_faces.push_back({dress.face_node(f, 0).idx, dress.face_node(f, 1).idx, dress.face_node(f, 2).idx});
  d->mass.assign(static_cast<std::size_t>(d->num_nodes), 1e-4);
  d->fixed.assign(static_cast<std::size_t>(d->num_nodes), 0);
  d->h = scene.frame_time / scene.substeps;
  d->band = scene.collision.repulsion_thickness;
  d->params = scene.collision;
  for (const ObstacleSpec& o : scene.obstacles) {
    CollisionMesh cm;
    for (FaceId f : o.mesh.faces()) cm.faces.push_back({o.mesh.face_node(f, 0).idx, o.mesh.face_node(f, 1).idx, o.mesh.face_node(f, 2).idx});
    d->body.push_back(cm);
    d->body_now.push_back(o.positions_at(sim.time()));
    d->body_next.push_back(o.positions_at(sim.time() + d->h));
    std::vector<Vec3> vel(d->body_now.back().size());
    for (std::size_t i = 0; i < vel.size(); ++i) vel[i] = (d->body_next.back()[i] - d->body_now.back()[i]) / d->h;
    d->body_v.push_back(vel);
  }
  slot = std::move(d);
  return *slot;
}

void BM_Detection(benchmark::State& state) {
  const DressedCharacter& d = dressed_character(static_cast<int>(state.range(0)));
  CollisionParams params = d.params;
  params.threads = static_cast<int>(state.range(1));
  Collider collider(d.cloth_faces, d.body, d.num_nodes);
  // The cloth moves with its velocity over the step: the usual continuous round with no impact.
  const Eigen::VectorXd x_next = d.x + d.h * d.v;
  double pairs = 0, impacts = 0;
  for (auto _ : state) {
    pairs += static_cast<double>(collider.proximities(d.x, d.v, d.fixed, d.body_now, d.body_v, d.band, params.threads).size());
    Eigen::VectorXd x_end = x_next;
    impacts += collider.resolve(d.x, x_end, d.mass, d.fixed, d.body_now, d.body_next, params).impacts;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["faces"] = static_cast<double>(d.cloth_faces.size());
  state.counters["proximity_pairs"] = pairs / n;
  state.counters["impacts"] = impacts / n;
  state.SetLabel(state.range(0) == 1 ? "adaptive" : "view");
}

// The candidate stage alone, as a proximity search meets it (boxes of the start positions, the
// repulsion band as padding), with callbacks that only count: the floor under BM_Detection's
// search that no narrow phase can lower. Same dress, one thread.
void BM_Candidates(benchmark::State& state) {
  const DressedCharacter& d = dressed_character(static_cast<int>(state.range(0)));
  std::set<std::array<int32_t, 2>> edge_set;
  for (const auto& f : d.cloth_faces)
    for (int k = 0; k < 3; ++k) edge_set.insert({std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])});
  const std::vector<std::array<int32_t, 2>> edges(edge_set.begin(), edge_set.end());
  std::vector<char> used(static_cast<std::size_t>(d.num_nodes), 0);
  for (const auto& f : d.cloth_faces)
    for (int32_t n : f) used[static_cast<std::size_t>(n)] = 1;
  auto x = [&](int32_t n) { return Vec3(d.x.segment<3>(3 * n)); };
  const Bvh faces(leaf_boxes(d.cloth_faces.size(), 1, [&](std::size_t i) {
    Aabb b;
    for (int32_t n : d.cloth_faces[i]) b.grow(x(n));
    return b;
  }));
  const Bvh edge_tree(leaf_boxes(edges.size(), 1, [&](std::size_t i) {
    Aabb b;
    for (int32_t n : edges[i]) b.grow(x(n));
    return b;
  }));
  std::vector<std::unique_ptr<Bvh>> body_faces, body_edges;
  std::vector<const Bvh*> obstacle_vertices, obstacle_faces, obstacle_edges;
  for (std::size_t o = 0; o < d.body.size(); ++o) {
    body_faces.push_back(std::make_unique<Bvh>(leaf_boxes(d.body[o].faces.size(), 1, [&](std::size_t i) {
      Aabb b;
      for (int32_t n : d.body[o].faces[i]) b.grow(d.body_now[o][static_cast<std::size_t>(n)]);
      return b;
    })));
    obstacle_faces.push_back(body_faces.back().get());
  }
  const CandidateTrees trees{d.cloth_faces, edges, used, faces, edge_tree, obstacle_vertices, obstacle_faces, obstacle_edges};
  double vertex_pairs = 0, edge_pairs = 0, tv = 0, te = 0;
  for (auto _ : state) {
    std::vector<int64_t> vf(used.size(), 0), ee(edges.size(), 0);
    auto t0 = std::chrono::steady_clock::now();
    vertex_face_candidates(
        trees, nullptr, nullptr, 1,
        [&](int32_t v) {
          Aabb b;
          b.grow(x(v));
          b.pad(d.band);
          return b;
        },
        [&](int32_t v, int32_t) { ++vf[static_cast<std::size_t>(v)]; }, [&](int32_t v, std::size_t, int32_t) { ++vf[static_cast<std::size_t>(v)]; });
    auto t1 = std::chrono::steady_clock::now();
    edge_edge_candidates(
        trees, nullptr, nullptr, d.band, 1, [&](int32_t a, int32_t) { ++ee[static_cast<std::size_t>(a)]; },
        [&](std::size_t, int32_t a, int32_t) { ++ee[static_cast<std::size_t>(a)]; });
    auto t2 = std::chrono::steady_clock::now();
    tv += std::chrono::duration<double, std::milli>(t1 - t0).count();
    te += std::chrono::duration<double, std::milli>(t2 - t1).count();
    for (int64_t c : vf) vertex_pairs += static_cast<double>(c);
    for (int64_t c : ee) edge_pairs += static_cast<double>(c);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["faces"] = static_cast<double>(d.cloth_faces.size());
  state.counters["vertex_face"] = vertex_pairs / n;
  state.counters["edge_edge"] = edge_pairs / n;
  state.counters["vf_ms"] = tv / n;
  state.counters["ee_ms"] = te / n;
  state.SetLabel(state.range(0) == 1 ? "adaptive" : "view");
}

// Modes: 1 adaptive, 2 view; threads 1 and 2.
BENCHMARK(BM_Detection)->ArgsProduct({{1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Candidates)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace vdc
