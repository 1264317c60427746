// Intersection contour minimisation (Volino and Magnenat-Thalmann 2006, section 3) for cloth-
// cloth crossings; obstacle crossings are pushed to the obstacle's outside.
#include "collision/untangle.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "collision/intersection.hpp"
#include "core/bvh.hpp"
#include "core/task_order.hpp"

namespace vdc {

namespace {

// Weight of the shorter-side term against the contour gradient (whose terms are unit vectors).
constexpr double kLocalWeight = 0.1;

// Edge (i, j) crossing face (a, b, c) at edge parameter t, face barycentrics `bary`.
struct Crossing {
  std::array<int32_t, 2> edge;
  std::array<int32_t, 3> face;
  double t = 0;
  Vec3 bary;
  Vec3 point;
};

std::optional<Crossing> edge_through_face(std::array<int32_t, 2> edge, std::array<int32_t, 3> face, const Vec3& p, const Vec3& q,
                                          const Vec3& a, const Vec3& b, const Vec3& c) {
  if (!segment_crosses_triangle(p, q, a, b, c)) return std::nullopt;
  const double sp = orient3(a, b, c, p), sq = orient3(a, b, c, q);
  const double e0 = orient3(p, q, a, b), e1 = orient3(p, q, b, c), e2 = orient3(p, q, c, a);
  const double sum = e0 + e1 + e2;
  if (sp == sq || sum == 0) return std::nullopt;
  Crossing k;
  k.edge = edge;
  k.face = face;
  k.t = sp / (sp - sq);
  k.bary = Vec3(e1, e2, e0) / sum;
  k.point = p + k.t * (q - p);
  return k;
}

class Untangler {
 public:
  Untangler(const std::vector<std::array<int32_t, 3>>& faces, Eigen::VectorXd& x, const std::vector<char>& fixed,
            const std::vector<CollisionMesh>& obstacles, const std::vector<std::vector<Vec3>>& obstacle_x,
            const std::vector<const Bvh*>& obstacle_trees, const UntangleParams& params)
      : faces_(faces), x_(x), fixed_(fixed), obstacles_(obstacles), obstacle_x_(obstacle_x), params_(params) {
    // The obstacles do not move while the cloth is untangled: one hierarchy each for all passes.
    obstacle_tree_ = face_trees_at(obstacles_, obstacle_x_, obstacle_trees, 1, built_);
  }

  UntangleReport run() {
    UntangleReport report;
    // The positions with the fewest crossing pairs so far: the moves are local and can make
    // things worse where pushes meet (a node pushed out of one face through a neighbour), so
    // the result is never worse than the best state seen, the start included.
    Eigen::VectorXd best_x;
    int best = -1;
    for (int it = 0; it <= params_.max_iterations; ++it) {
      const std::size_t n = static_cast<std::size_t>(x_.size() / 3);
      gradient_.assign(n, Vec3::Zero());
      push_.assign(n, Vec3::Zero());
      const auto [cloth_pairs, obstacle_pairs] = detect();
      if (it == 0) {
        report.cloth_pairs = cloth_pairs;
        report.obstacle_pairs = obstacle_pairs;
      }
      report.remaining = cloth_pairs + obstacle_pairs;
      if (best < 0 || report.remaining < best) {
        best = report.remaining;
        if (best > 0) best_x = x_;
      }
      if (report.remaining == 0 || it == params_.max_iterations) break;
      ++report.iterations;
      const int moved = move();
      report.moves += moved;
      if (moved == 0) break;  // nothing can move (crossings that only touch, or held nodes)
    }
    if (report.remaining > best) {
      x_ = best_x;
      report.restored_pairs = report.remaining;
      report.remaining = best;
    }
    return report;
  }

 private:
  Vec3 at(int32_t i) const { return x_.segment<3>(3 * i); }

  // One pass over all triangle pairs: counts intersecting pairs and accumulates the contour
  // gradient (cloth-cloth) and the pushes out of obstacles.
  std::pair<int, int> detect() {
    const std::vector<Aabb> boxes = leaf_boxes(faces_.size(), params_.threads, [&](std::size_t f) {
      Aabb box;
      for (int32_t v : faces_[f]) box.grow(at(v));
      return box;
    });
    const Bvh tree(boxes, params_.threads);
    // The candidate pairs in the hierarchy's order, tested for a crossing in parallel (a pure
    // test), then those that cross taken in that order: the gradient and the pushes add up as
    // on one thread.
    std::vector<std::pair<int32_t, int32_t>> cloth;
    tree.self_pairs([&](int32_t fa, int32_t fb) {
      const auto &A = faces_[static_cast<std::size_t>(fa)], &B = faces_[static_cast<std::size_t>(fb)];
      for (int32_t v : A)
        if (v == B[0] || v == B[1] || v == B[2]) return;
      cloth.emplace_back(fa, fb);
    });
    const std::vector<char> cloth_crossing = flags(cloth.size(), [&](std::size_t k) {
      return !crossings_between(faces_[static_cast<std::size_t>(cloth[k].first)], faces_[static_cast<std::size_t>(cloth[k].second)]).empty();
    });
    int cloth_pairs = 0, obstacle_pairs = 0;
    for (std::size_t k = 0; k < cloth.size(); ++k)
      if (cloth_crossing[k] && cloth_contour(faces_[static_cast<std::size_t>(cloth[k].first)], faces_[static_cast<std::size_t>(cloth[k].second)]))
        ++cloth_pairs;
    // The pairs with each obstacle in index order: its hierarchy may be the collider's, kept
    // from step to step, or one built afresh (after a resumption), which meet them in different
    // orders, and the pushes add up in this one.
    for (std::size_t o = 0; o < obstacles_.size(); ++o) {
      const auto& ox = obstacle_x_[o];
      std::vector<std::pair<int32_t, int32_t>> pairs;
      tree.pairs_with(*obstacle_tree_[o], [&](int32_t fc, int32_t fo) { pairs.emplace_back(fc, fo); });
      std::sort(pairs.begin(), pairs.end());
      const std::vector<char> crossing = flags(pairs.size(), [&](std::size_t k) {
        return obstacle_crosses(faces_[static_cast<std::size_t>(pairs[k].first)], obstacles_[o].faces[static_cast<std::size_t>(pairs[k].second)], ox);
      });
      for (std::size_t k = 0; k < pairs.size(); ++k)
        if (crossing[k] &&
            obstacle_push(faces_[static_cast<std::size_t>(pairs[k].first)], obstacles_[o].faces[static_cast<std::size_t>(pairs[k].second)], ox))
          ++obstacle_pairs;
    }
    return {cloth_pairs, obstacle_pairs};
  }

  // test(k) for k in [0, n), on the threads.
  template <class Test>
  std::vector<char> flags(std::size_t n, Test&& test) const {
    std::vector<char> out(n, 0);
    for_each_index(static_cast<int64_t>(n), params_.threads,
                   [&](int64_t k) { out[static_cast<std::size_t>(k)] = test(static_cast<std::size_t>(k)) ? 1 : 0; });
    return out;
  }

  // Whether obstacle_push finds a crossing of cloth face C and obstacle face O.
  static bool obstacle_crosses_at(const std::array<Vec3, 3>& c, const Vec3& a, const Vec3& b, const Vec3& o) {
    for (int i = 0; i < 3; ++i)
      if (segment_crosses_triangle(c[static_cast<std::size_t>(i)], c[static_cast<std::size_t>((i + 1) % 3)], a, b, o)) return true;
    return false;
  }
  bool obstacle_crosses(const std::array<int32_t, 3>& C, const std::array<int32_t, 3>& O, const std::vector<Vec3>& ox) const {
    const Vec3 &a = ox[static_cast<std::size_t>(O[0])], &b = ox[static_cast<std::size_t>(O[1])], &c = ox[static_cast<std::size_t>(O[2])];
    if (area_normal(a, b, c).squaredNorm() == 0) return false;
    if (obstacle_crosses_at({at(C[0]), at(C[1]), at(C[2])}, a, b, c)) return true;
    return obstacle_crosses_at({a, b, c}, at(C[0]), at(C[1]), at(C[2]));
  }

  // The contour segment of two crossing cloth faces: its two ends are edge-face crossings; the
  // length |P1 - P2| has gradient u at P1 and -u at P2, taken to the nodes through each
  // crossing's dependence on a translation of its edge relative to its face.
  // The edge-face crossings of two cloth faces: each one's edges through the other.
  std::vector<Crossing> crossings_between(const std::array<int32_t, 3>& A, const std::array<int32_t, 3>& B) const {
    std::vector<Crossing> ks;
    auto edges_through = [&](const std::array<int32_t, 3>& E, const std::array<int32_t, 3>& F) {
      for (int i = 0; i < 3; ++i) {
        const int32_t p = E[static_cast<std::size_t>(i)], q = E[static_cast<std::size_t>((i + 1) % 3)];
        if (auto k = edge_through_face({p, q}, F, at(p), at(q), at(F[0]), at(F[1]), at(F[2]))) ks.push_back(*k);
      }
    };
    edges_through(A, B);
    edges_through(B, A);
    return ks;
  }

  bool cloth_contour(const std::array<int32_t, 3>& A, const std::array<int32_t, 3>& B) {
    const std::vector<Crossing> ks = crossings_between(A, B);
    if (ks.empty()) return false;
    if (ks.size() < 2) return true;  // touching at a point: counted, no direction to move
    std::size_t i1 = 0, i2 = 1;
    double best = -1;
    for (std::size_t i = 0; i < ks.size(); ++i)
      for (std::size_t j = i + 1; j < ks.size(); ++j)
        if (const double d = (ks[i].point - ks[j].point).squaredNorm(); d > best) best = d, i1 = i, i2 = j;
    if (best <= 0) return true;
    const Vec3 u = (ks[i1].point - ks[i2].point) / std::sqrt(best);
    add_gradient(ks[i1], u);
    add_gradient(ks[i2], -u);
    return true;
  }

  // dL/dP = w at a crossing; P moves with a translation d of the edge relative to the face as
  // dP = (I - e N^T / (N . e)) d, so dL/dd = w - N (e . w) / (N . e).
  void add_gradient(const Crossing& k, const Vec3& w) {
    const Vec3 e = at(k.edge[1]) - at(k.edge[0]);
    const Vec3 n = area_normal(at(k.face[0]), at(k.face[1]), at(k.face[2])).normalized();
    double ne = n.dot(e);
    const double floor = 0.05 * e.norm();  // an edge grazing the face's plane: bounded gradient
    if (std::abs(ne) < floor) ne = ne < 0 ? -floor : floor;
    Vec3 g = w - n * (e.dot(w) / ne);
    // Where the contour is straight its length has no gradient (a strip of one sheet through
    // another); a small term then sends the edge's shorter part back through the face.
    const Vec3 shorter = k.t < 0.5 ? at(k.edge[0]) : at(k.edge[1]);
    g += (n.dot(shorter - k.point) >= 0 ? kLocalWeight : -kLocalWeight) * n;
    gradient_[static_cast<std::size_t>(k.edge[0])] += (1 - k.t) * g;
    gradient_[static_cast<std::size_t>(k.edge[1])] += k.t * g;
    for (int c = 0; c < 3; ++c) gradient_[static_cast<std::size_t>(k.face[static_cast<std::size_t>(c)])] -= k.bary[c] * g;
  }

  // A cloth face against an obstacle face: a cloth edge through the obstacle moves its inner end
  // out along the obstacle normal to the thickness; an obstacle edge through the cloth face moves
  // the face one step along the obstacle normal.
  bool obstacle_push(const std::array<int32_t, 3>& C, const std::array<int32_t, 3>& O, const std::vector<Vec3>& ox) {
    const Vec3 &a = ox[static_cast<std::size_t>(O[0])], &b = ox[static_cast<std::size_t>(O[1])], &c = ox[static_cast<std::size_t>(O[2])];
    const Vec3 an = area_normal(a, b, c);
    if (an.squaredNorm() == 0) return false;
    const Vec3 n = an.normalized();
    bool crossed = false;
    auto propose = [&](int32_t v, const Vec3& d) {
      Vec3& p = push_[static_cast<std::size_t>(v)];
      if (d.squaredNorm() > p.squaredNorm()) p = d;
    };
    for (int i = 0; i < 3; ++i) {
      const int32_t p = C[static_cast<std::size_t>(i)], q = C[static_cast<std::size_t>((i + 1) % 3)];
      if (!segment_crosses_triangle(at(p), at(q), a, b, c)) continue;
      crossed = true;
      for (int32_t v : {p, q}) {
        const double height = n.dot(at(v) - a);
        if (height < params_.thickness) propose(v, (params_.thickness - height) * n);
      }
    }
    for (int i = 0; i < 3; ++i) {
      const Vec3 &p = ox[static_cast<std::size_t>(O[static_cast<std::size_t>(i)])], &q = ox[static_cast<std::size_t>(O[static_cast<std::size_t>((i + 1) % 3)])];
      if (!segment_crosses_triangle(p, q, at(C[0]), at(C[1]), at(C[2]))) continue;
      crossed = true;
      for (int32_t v : C) propose(v, params_.step * n);
    }
    return crossed;
  }

  // Moves every node: down the contour gradient, scaled so the steepest moves one step (nodes
  // within a tenth of the steepest move a full step), plus its push out of obstacles.
  int move() {
    double g_max = 0;
    for (const Vec3& g : gradient_) g_max = std::max(g_max, g.norm());
    int moves = 0;
    for (std::size_t i = 0; i < gradient_.size(); ++i) {
      if (fixed_[i]) continue;
      Vec3 d = push_[i];
      const double g = gradient_[i].norm();
      if (g > 0) d -= params_.step * gradient_[i] / std::max(g, 0.1 * g_max);
      if (d.squaredNorm() == 0) continue;
      x_.segment<3>(3 * static_cast<int64_t>(i)) += d;
      ++moves;
    }
    return moves;
  }

  const std::vector<std::array<int32_t, 3>>& faces_;
  Eigen::VectorXd& x_;
  const std::vector<char>& fixed_;
  const std::vector<CollisionMesh>& obstacles_;
  const std::vector<std::vector<Vec3>>& obstacle_x_;
  std::vector<const Bvh*> obstacle_tree_;     // per obstacle: boxes holding its faces
  std::vector<std::unique_ptr<Bvh>> built_;  // the ones not given
  const UntangleParams& params_;
  std::vector<Vec3> gradient_, push_;
};

}  // namespace

UntangleReport untangle(const std::vector<std::array<int32_t, 3>>& cloth_faces, Eigen::VectorXd& x, const std::vector<char>& fixed,
                        const std::vector<CollisionMesh>& obstacles, const std::vector<std::vector<Vec3>>& obstacle_x,
                        const UntangleParams& params, const std::vector<const Bvh*>& obstacle_trees) {
  return Untangler(cloth_faces, x, fixed, obstacles, obstacle_x, obstacle_trees, params).run();
}

}  // namespace vdc
