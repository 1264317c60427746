// The candidate stage: on a crumpled sheet and an obstacle beside it, every query finds exactly
// the primitives whose boxes meet its box (counted against all pairs, by hand), never a pair that
// shares a node, each cloth edge pair once; after a round that moved some nodes, exactly the
// pairs with a moved node.
#include "collision/candidates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <random>
#include <set>
#include <tuple>

namespace vdc {
namespace {

class CandidatesTest : public ::testing::Test {
 protected:
  // A 7 x 7 grid of nodes, its heights random, as 72 faces and their edges; a two-face obstacle
  // through it; every primitive's box its points' box padded by 0.05.
  void SetUp() override {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> height(-0.15, 0.15);
    constexpr int kSide = 7;
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) x_.emplace_back(0.1 * i, height(rng), 0.1 * j);
    auto id = [&](int i, int j) { return static_cast<int32_t>(j * kSide + i); };
    for (int j = 0; j + 1 < kSide; ++j)
      for (int i = 0; i + 1 < kSide; ++i) {
        faces_.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        faces_.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    std::set<std::array<int32_t, 2>> edges;
    for (const auto& f : faces_)
      for (int k = 0; k < 3; ++k) edges.insert({std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])});
    edges_.assign(edges.begin(), edges.end());
    used_.assign(x_.size(), 1);
    obstacle_x_ = {{0.3, -0.18, 0.3}, {0.3, 0.18, 0.3}, {0.3, 0.18, -0.1}, {0.3, -0.18, -0.1}};
    obstacle_faces_ = {{0, 1, 2}, {0, 2, 3}};
    obstacle_edges_ = {{0, 1}, {1, 2}, {0, 2}, {2, 3}, {0, 3}};
    for (const auto& f : faces_) face_boxes_.push_back(box({x_[f[0]], x_[f[1]], x_[f[2]]}));
    for (const auto& e : edges_) edge_boxes_.push_back(box({x_[e[0]], x_[e[1]]}));
    for (const auto& f : obstacle_faces_) obstacle_face_boxes_.push_back(box({obstacle_x_[f[0]], obstacle_x_[f[1]], obstacle_x_[f[2]]}));
    for (const auto& e : obstacle_edges_) obstacle_edge_boxes_.push_back(box({obstacle_x_[e[0]], obstacle_x_[e[1]]}));
    face_tree_ = std::make_unique<Bvh>(face_boxes_);
    edge_tree_ = std::make_unique<Bvh>(edge_boxes_);
    std::vector<Aabb> obstacle_points;  // unpadded: the candidate stage grows them by its pad
    for (const Vec3& p : obstacle_x_) obstacle_points.push_back(box({p}, 0.0));
    obstacle_vertex_tree_ = std::make_unique<Bvh>(obstacle_points);
    obstacle_face_tree_ = std::make_unique<Bvh>(obstacle_face_boxes_);
    obstacle_edge_tree_ = std::make_unique<Bvh>(obstacle_edge_boxes_);
    obstacle_vertex_trees_ = {obstacle_vertex_tree_.get()};
    obstacle_face_trees_ = {obstacle_face_tree_.get()};
    obstacle_edge_trees_ = {obstacle_edge_tree_.get()};
  }
  static Aabb box(std::initializer_list<Vec3> points, double pad = kPad) {
    Aabb b;
    for (const Vec3& p : points) b.grow(p);
    b.pad(pad);
    return b;
  }
  CandidateTrees trees() const {
    return {faces_, edges_, used_, *face_tree_, *edge_tree_, obstacle_vertex_trees_, obstacle_face_trees_, obstacle_edge_trees_};
  }
  static bool shares(const std::array<int32_t, 3>& f, int32_t v) { return f[0] == v || f[1] == v || f[2] == v; }
  static bool shares(const std::array<int32_t, 2>& a, const std::array<int32_t, 2>& b) {
    return a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1];
  }

  using Found = std::multiset<std::tuple<int, int, int>>;  // (obstacle or -1, query, candidate)
  // What each query of the stage finds, with `moved` (or none) and `threads`.
  Found vertex_faces(const MovedPrimitives* moved, int threads, const KeptClothPairs* listed = nullptr) const {
    Found found;
    std::mutex lock;
    vertex_face_candidates(
        trees(), moved, listed, threads, [&](int32_t v) { return box({x_[static_cast<std::size_t>(v)]}); },
        [&](int32_t v, int32_t f) {
          std::lock_guard<std::mutex> hold(lock);
          found.insert({-1, v, f});
        },
        [&](int32_t v, std::size_t o, int32_t f) {
          std::lock_guard<std::mutex> hold(lock);
          found.insert({static_cast<int>(o), v, f});
        });
    return found;
  }
  Found obstacle_vertices(const MovedPrimitives* moved, int threads) const {
    Found found;
    std::mutex lock;
    obstacle_vertex_candidates(trees(), moved, kPad, threads, [&](std::size_t o, int32_t v, int32_t f) {
      std::lock_guard<std::mutex> hold(lock);
      found.insert({static_cast<int>(o), v, f});
    });
    return found;
  }
  Found edge_pairs(const MovedPrimitives* moved, int threads, const KeptClothPairs* listed = nullptr) const {
    Found found;
    std::mutex lock;
    edge_edge_candidates(
        trees(), moved, listed, 0.0, threads,
        [&](int32_t a, int32_t b) {
          std::lock_guard<std::mutex> hold(lock);
          found.insert({-1, std::min(a, b), std::max(a, b)});
        },
        [&](std::size_t o, int32_t a, int32_t b) {
          std::lock_guard<std::mutex> hold(lock);
          found.insert({static_cast<int>(o), a, b});
        });
    return found;
  }

  std::vector<Vec3> x_, obstacle_x_;
  std::vector<std::array<int32_t, 3>> faces_, obstacle_faces_;
  std::vector<std::array<int32_t, 2>> edges_, obstacle_edges_;
  std::vector<char> used_;
  std::vector<Aabb> face_boxes_, edge_boxes_, obstacle_face_boxes_, obstacle_edge_boxes_;
  static constexpr double kPad = 0.05;
  std::unique_ptr<Bvh> face_tree_, edge_tree_, obstacle_vertex_tree_, obstacle_face_tree_, obstacle_edge_tree_;
  std::vector<const Bvh*> obstacle_vertex_trees_, obstacle_face_trees_, obstacle_edge_trees_;
};

TEST_F(CandidatesTest, EveryQueryFindsExactlyTheBoxesItMeets) {
  Found vf, ov, ee;
  for (int32_t v = 0; v < static_cast<int32_t>(x_.size()); ++v) {
    const Aabb b = box({x_[static_cast<std::size_t>(v)]});
    for (int32_t f = 0; f < static_cast<int32_t>(faces_.size()); ++f)
      if (!shares(faces_[static_cast<std::size_t>(f)], v) && b.overlaps(face_boxes_[static_cast<std::size_t>(f)])) vf.insert({-1, v, f});
    for (int32_t f = 0; f < static_cast<int32_t>(obstacle_faces_.size()); ++f)
      if (b.overlaps(obstacle_face_boxes_[static_cast<std::size_t>(f)])) vf.insert({0, v, f});
  }
  for (int32_t v = 0; v < static_cast<int32_t>(obstacle_x_.size()); ++v)
    for (int32_t f = 0; f < static_cast<int32_t>(faces_.size()); ++f)
      if (box({obstacle_x_[static_cast<std::size_t>(v)]}).overlaps(face_boxes_[static_cast<std::size_t>(f)])) ov.insert({0, v, f});
  for (int32_t a = 0; a < static_cast<int32_t>(edges_.size()); ++a) {
    const Aabb& ba = edge_boxes_[static_cast<std::size_t>(a)];
    for (int32_t b = a + 1; b < static_cast<int32_t>(edges_.size()); ++b)
      if (!shares(edges_[static_cast<std::size_t>(a)], edges_[static_cast<std::size_t>(b)]) && ba.overlaps(edge_boxes_[static_cast<std::size_t>(b)]))
        ee.insert({-1, a, b});
    for (int32_t b = 0; b < static_cast<int32_t>(obstacle_edges_.size()); ++b)
      if (ba.overlaps(obstacle_edge_boxes_[static_cast<std::size_t>(b)])) ee.insert({0, a, b});
  }
  // The scene is crumpled enough that each kind has candidates, and fewer than all pairs.
  EXPECT_GT(vf.size(), 100u);
  EXPECT_GT(ov.size(), 0u);
  EXPECT_GT(ee.size(), 100u);
  EXPECT_LT(ee.size(), edges_.size() * edges_.size() / 4);
  for (const int threads : {1, 3}) {
    EXPECT_EQ(vertex_faces(nullptr, threads), vf) << threads;
    EXPECT_EQ(obstacle_vertices(nullptr, threads), ov) << threads;
    EXPECT_EQ(edge_pairs(nullptr, threads), ee) << threads;  // a multiset: each pair once
  }

  // Nodes 8, 9 and 30 moved: what remains has a moved node, or is an obstacle met by a moved one.
  std::vector<char> moved(x_.size(), 0);
  for (const int n : {8, 9, 30}) moved[static_cast<std::size_t>(n)] = 1;
  const MovedPrimitives only_moved(moved, trees(), face_boxes_, edge_boxes_);
  auto moved_face = [&](int f) { return moved[faces_[f][0]] || moved[faces_[f][1]] || moved[faces_[f][2]]; };
  auto moved_edge = [&](int e) { return moved[edges_[e][0]] || moved[edges_[e][1]]; };
  Found vf_moved, ov_moved, ee_moved;
  for (const auto& [o, v, f] : vf)
    if (moved[v] || (o < 0 && moved_face(f))) vf_moved.insert({o, v, f});
  for (const auto& [o, v, f] : ov)
    if (moved_face(f)) ov_moved.insert({o, v, f});
  for (const auto& [o, a, b] : ee)
    if (moved_edge(a) || (o < 0 && moved_edge(b))) ee_moved.insert({o, a, b});
  EXPECT_LT(vf_moved.size(), vf.size());
  EXPECT_GT(vf_moved.size(), 0u);
  EXPECT_EQ(vertex_faces(&only_moved, 2), vf_moved);
  EXPECT_EQ(obstacle_vertices(&only_moved, 2), ov_moved);
  EXPECT_EQ(edge_pairs(&only_moved, 2), ee_moved);
}

// A body-sized obstacle: 1,600 vertices on a wavy sheet crossing the cloth, their hierarchy
// descended with the cloth's from many subtrees. Each vertex meets exactly the cloth faces whose
// boxes meet its box grown by the pad (counted against all pairs), each pair once, on one and
// three threads; after a round that moved three nodes, exactly the moved faces among them.
TEST_F(CandidatesTest, ObstacleVerticesDescendingWithTheClothFindExactlyTheBoxesTheyMeet) {
  constexpr int kSide = 40;
  std::vector<Vec3> body;
  std::vector<Aabb> points;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const double u = -0.2 + 1.0 * i / (kSide - 1), w = -0.2 + 1.0 * j / (kSide - 1);
      body.emplace_back(u, 0.12 * std::sin(9.0 * u) * std::cos(7.0 * w), w);
      points.push_back(box({body.back()}, 0.0));
    }
  const Bvh body_tree(points);
  const std::vector<const Bvh*> vertex_trees{&body_tree};
  ASSERT_GT(body_tree.subtrees(kCandidateTraversalUnits).size(), 32u);
  const CandidateTrees t{faces_, edges_, used_, *face_tree_, *edge_tree_, vertex_trees, obstacle_face_trees_, obstacle_edge_trees_};
  auto found_with = [&](const MovedPrimitives* moved, int threads) {
    Found found;
    std::mutex lock;
    obstacle_vertex_candidates(t, moved, kPad, threads, [&](std::size_t o, int32_t v, int32_t f) {
      std::lock_guard<std::mutex> hold(lock);
      found.insert({static_cast<int>(o), v, f});
    });
    return found;
  };
  std::vector<char> moved(x_.size(), 0);
  for (const int n : {8, 9, 30}) moved[static_cast<std::size_t>(n)] = 1;
  auto moved_face = [&](int f) { return moved[faces_[f][0]] || moved[faces_[f][1]] || moved[faces_[f][2]]; };
  Found all, of_moved;
  for (int32_t v = 0; v < static_cast<int32_t>(body.size()); ++v)
    for (int32_t f = 0; f < static_cast<int32_t>(faces_.size()); ++f)
      if (box({body[static_cast<std::size_t>(v)]}).overlaps(face_boxes_[static_cast<std::size_t>(f)])) {
        all.insert({0, v, f});
        if (moved_face(f)) of_moved.insert({0, v, f});
      }
  EXPECT_GT(all.size(), 1000u);
  EXPECT_LT(all.size(), body.size() * faces_.size() / 4);
  EXPECT_GT(of_moved.size(), 0u);
  const MovedPrimitives only_moved(moved, trees(), face_boxes_, edge_boxes_);
  for (const int threads : {1, 3}) {
    EXPECT_EQ(found_with(nullptr, threads), all) << threads;  // a multiset: each pair once
    EXPECT_EQ(found_with(&only_moved, threads), of_moved) << threads;
  }
}

// A first round of continuous detection from the cloth pairs a proximity search met (pad 0.05)
// some steps before, the sheet moved on since: with most nodes near where the search found them
// once the common motion is taken out and three moved far, vertex-face and edge-edge candidates
// are exactly those a search of the swept boxes finds.
TEST_F(CandidatesTest, AFirstRoundFromTheProximityListsFindsWhatASearchOfTheSweptBoxesFinds) {
  const double pad = 0.05, eta = 1e-4;
  auto boxes_of = [](const auto& items, auto&& box) {
    std::vector<Aabb> out;
    for (const auto& item : items) out.push_back(box(item));
    return out;
  };
  auto hull = [](std::initializer_list<Vec3> points, double grow) {
    Aabb b;
    for (const Vec3& p : points) b.grow(p);
    b.pad(grow);
    return b;
  };
  auto bvh = [](const std::vector<Aabb>& b) { return std::make_unique<Bvh>(b); };
  // The proximity search at the start: unpadded boxes, the query side grown by the pad.
  const auto start_faces = boxes_of(faces_, [&](const auto& f) { return hull({x_[f[0]], x_[f[1]], x_[f[2]]}, 0); });
  const auto start_edges = boxes_of(edges_, [&](const auto& e) { return hull({x_[e[0]], x_[e[1]]}, 0); });
  const auto start_face_tree = bvh(start_faces), start_edge_tree = bvh(start_edges);
  const CandidateTrees start{faces_, edges_, used_, *start_face_tree, *start_edge_tree, obstacle_vertex_trees_, obstacle_face_trees_, obstacle_edge_trees_};
  KeptClothPairs kept;
  kept.clear(x_.size(), edges_.size());
  kept.pad = pad;
  vertex_face_candidates(
      start, nullptr, nullptr, 2, [&](int32_t v) { return hull({x_[static_cast<std::size_t>(v)]}, pad); },
      [&](int32_t v, int32_t f) { kept.node_faces[static_cast<std::size_t>(v)].push_back(f); }, [](int32_t, std::size_t, int32_t) {});
  edge_edge_candidates(
      start, nullptr, nullptr, pad, 2,
      [&](int32_t a, int32_t b) { kept.edge_edges[static_cast<std::size_t>(a)].push_back(b); }, [](std::size_t, int32_t, int32_t) {});
  // Steps later the whole sheet has moved 0.3 m, far past the lists' reach: this step starts
  // there and moves every node up to a third of the reach in each coordinate, nodes 8, 24 and 40
  // much farther. Taking out the common motion leaves those three beyond the reach.
  std::mt19937 rng(3);
  const double r = kept.reach(2 * eta);
  std::uniform_real_distribution<double> within(-r / 3, r / 3);
  std::vector<Vec3> begin = x_, end = x_;
  for (std::size_t n = 0; n < x_.size(); ++n) {
    begin[n] += Vec3(0.3, 0.1, -0.2) + Vec3(within(rng), within(rng), within(rng));
    end[n] = begin[n] + Vec3(within(rng), within(rng), within(rng));
  }
  for (const int n : {8, 24, 40}) end[static_cast<std::size_t>(n)] += Vec3(0.2, -0.15, 0.1);
  const auto swept_faces =
      boxes_of(faces_, [&](const auto& f) { return hull({begin[f[0]], begin[f[1]], begin[f[2]], end[f[0]], end[f[1]], end[f[2]]}, eta); });
  const auto swept_edges = boxes_of(edges_, [&](const auto& e) { return hull({begin[e[0]], begin[e[1]], end[e[0]], end[e[1]]}, eta); });
  const auto face_tree = bvh(swept_faces), edge_tree = bvh(swept_edges);
  const CandidateTrees swept{faces_, edges_, used_, *face_tree, *edge_tree, obstacle_vertex_trees_, obstacle_face_trees_, obstacle_edge_trees_};
  auto stacked = [](const std::vector<Vec3>& p) {
    Eigen::VectorXd v(3 * static_cast<Eigen::Index>(p.size()));
    for (std::size_t n = 0; n < p.size(); ++n) v.segment<3>(3 * static_cast<Eigen::Index>(n)) = p[n];
    return v;
  };
  kept.x = stacked(x_);
  const std::vector<char> far = kept.beyond(stacked(begin), stacked(end), 2 * eta, used_);
  EXPECT_EQ(std::count(far.begin(), far.end(), 1), 3);
  EXPECT_TRUE(far[8] && far[24] && far[40]);
  const MovedPrimitives moved(far, swept, swept_faces, swept_edges);
  auto vertex_box = [&](int32_t v) { return hull({begin[static_cast<std::size_t>(v)], end[static_cast<std::size_t>(v)]}, eta); };
  for (const int threads : {1, 2}) {
    Found vf_all, vf_listed, ee_all, ee_listed;
    std::mutex lock;
    auto into = [&](Found& found) {
      return [&found, &lock](int o, int32_t a, int32_t b) {
        std::lock_guard<std::mutex> hold(lock);
        found.insert({o, a, b});
      };
    };
    auto search = [&](const MovedPrimitives* m, const KeptClothPairs* listed, Found& vf, Found& ee) {
      auto add_vf = into(vf);
      auto add_ee = into(ee);
      vertex_face_candidates(
          swept, m, listed, threads, vertex_box, [&](int32_t v, int32_t f) { add_vf(-1, v, f); },
          [&](int32_t v, std::size_t o, int32_t f) { add_vf(static_cast<int>(o), v, f); });
      edge_edge_candidates(
          swept, m, listed, 0.0, threads,
          [&](int32_t a, int32_t b) { add_ee(-1, std::min(a, b), std::max(a, b)); },
          [&](std::size_t o, int32_t a, int32_t b) { add_ee(static_cast<int>(o), a, b); });
    };
    search(nullptr, nullptr, vf_all, ee_all);
    search(&moved, &kept, vf_listed, ee_listed);
    EXPECT_GT(vf_all.size(), 50u);
    EXPECT_GT(ee_all.size(), 100u);
    EXPECT_EQ(vf_listed, vf_all) << threads;
    EXPECT_EQ(ee_listed, ee_all) << threads;  // a multiset: each pair once
    // The lists alone, the three nodes that moved far taken for slow, miss pairs.
    const std::vector<char> none(x_.size(), 0);
    const MovedPrimitives nothing_far(none, swept, swept_faces, swept_edges);
    Found vf_lists, ee_lists;
    search(&nothing_far, &kept, vf_lists, ee_lists);
    EXPECT_LT(vf_lists.size(), vf_all.size());
    EXPECT_LT(ee_lists.size(), ee_all.size());
  }
}

}  // namespace
}  // namespace vdc
