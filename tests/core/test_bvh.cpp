// Bounding-volume hierarchy: every overlapping pair is reported, once, and no other, compared
// with the brute-force answer; refit follows moved boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "core/bvh.hpp"

namespace vdc {
namespace {

std::vector<Aabb> random_boxes(std::mt19937& rng, int n, double spread) {
  std::uniform_real_distribution<double> U(-spread, spread), S(0.01, 0.2);
  std::vector<Aabb> boxes(static_cast<std::size_t>(n));
  for (auto& b : boxes) {
    Vec3 c(U(rng), U(rng), U(rng));
    b.grow(c);
    b.grow(Vec3(c + Vec3(S(rng), S(rng), S(rng))));
  }
  return boxes;
}

std::set<std::pair<int, int>> brute_self(const std::vector<Aabb>& boxes) {
  std::set<std::pair<int, int>> out;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].overlaps(boxes[j])) out.emplace(static_cast<int>(i), static_cast<int>(j));
  return out;
}

// The boxes a query with `probe` must report, and those `tree` reports.
std::set<int> brute_query(const std::vector<Aabb>& boxes, const Aabb& probe) {
  std::set<int> out;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (boxes[i].overlaps(probe)) out.insert(static_cast<int>(i));
  return out;
}
std::set<int> queried(const Bvh& tree, const Aabb& probe) {
  std::set<int> out;
  tree.query(probe, [&](int32_t i) { out.insert(i); });
  return out;
}

TEST(Bvh, SelfPairsMatchBruteForceBeforeAndAfterRefit) {
  std::mt19937 rng(5);
  auto boxes = random_boxes(rng, 400, 1.0);
  Bvh bvh(boxes);
  for (int round = 0; round < 2; ++round) {
    std::multiset<std::pair<int, int>> found;
    bvh.self_pairs([&](int32_t i, int32_t j) { found.emplace(i, j); });
    auto expected = brute_self(boxes);
    EXPECT_EQ(found.size(), expected.size());
    const std::set<std::pair<int, int>> unique(found.begin(), found.end());
    EXPECT_EQ(unique, expected);
    for (auto& b : boxes) {  // move every box a little and refit
      Vec3 d(0.05 * std::sin(b.lo.x() * 7), 0.05 * std::cos(b.lo.y() * 5), 0.03);
      b.lo += d;
      b.hi += d;
    }
    bvh.refit(boxes);
  }
}

// Every primitive querying the tree for the ones after it meets each overlapping pair exactly
// once, before and after a refit (the leaf order is the tree's, so refits keep it).
TEST(Bvh, QueriesOfLaterPrimitivesMeetEachPairOnce) {
  std::mt19937 rng(11);
  std::vector<Aabb> boxes = random_boxes(rng, 400, 1.0);
  Bvh tree(boxes);
  for (int pass = 0; pass < 2; ++pass) {
    std::set<std::pair<int, int>> met;
    int meetings = 0;
    for (int32_t i = 0; i < tree.size(); ++i)
      tree.query_later(boxes[static_cast<std::size_t>(i)], i, [&](int32_t j) {
        EXPECT_NE(i, j);
        met.emplace(std::min(i, j), std::max(i, j));
        ++meetings;
      });
    EXPECT_EQ(met, brute_self(boxes)) << "pass " << pass;
    EXPECT_EQ(meetings, static_cast<int>(met.size())) << "pass " << pass;
    EXPECT_GT(met.size(), 50u);
    for (auto& b : boxes) {
      const Vec3 d = 0.05 * Vec3(std::uniform_real_distribution<double>(-1, 1)(rng), 0.3, -0.2);
      b.lo += d;
      b.hi += d;
    }
    tree.refit(boxes);
  }
}

// Units of work cover every primitive once, and descending from each unit finds, with a pad,
// exactly the pairs whose boxes are within the pad of each other: each pair once within a tree
// (from its earlier member's unit), every pair between two trees.
TEST(Bvh, DescentsFromSubtreesMeetEachPaddedPairOnce) {
  std::mt19937 rng(17);
  const std::vector<Aabb> a = random_boxes(rng, 500, 1.0), b = random_boxes(rng, 300, 1.0);
  const Bvh ta(a), tb(b);
  const double pad = 0.03;
  auto near = [&](const Aabb& p, const Aabb& q) {
    Aabb g = p;
    g.pad(pad);
    return g.overlaps(q);
  };
  std::set<std::pair<int, int>> self_expected, cross_expected;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = i + 1; j < a.size(); ++j)
      if (near(a[i], a[j])) self_expected.emplace(static_cast<int>(i), static_cast<int>(j));
    for (std::size_t j = 0; j < b.size(); ++j)
      if (near(a[i], b[j])) cross_expected.emplace(static_cast<int>(i), static_cast<int>(j));
  }
  Aabb everything;
  everything.grow(Vec3::Constant(-10));
  everything.grow(Vec3::Constant(10));
  const Bvh all({everything});
  for (int count : {1, 7, 64, 2000}) {
    const std::vector<int32_t> units = ta.subtrees(count);
    EXPECT_GE(static_cast<int>(units.size()), std::min(count, ta.leaves())) << count;
    std::vector<int> owner(a.size(), -1);
    std::set<std::pair<int, int>> self_found, cross_found;
    int self_meetings = 0;
    for (std::size_t u = 0; u < units.size(); ++u) {
      ta.pairs_under(units[u], all, 0.0, [&](int32_t i, int32_t) {
        EXPECT_EQ(owner[static_cast<std::size_t>(i)], -1) << "primitive " << i << " in two units";
        owner[static_cast<std::size_t>(i)] = static_cast<int>(u);
      });
      ta.later_pairs_under(units[u], pad, [&](int32_t i, int32_t j) {
        EXPECT_EQ(owner[static_cast<std::size_t>(i)], static_cast<int>(u));
        self_found.emplace(std::min(i, j), std::max(i, j));
        ++self_meetings;
      });
      ta.pairs_under(units[u], tb, pad, [&](int32_t i, int32_t j) { EXPECT_TRUE(cross_found.emplace(i, j).second); });
    }
    EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << count;
    EXPECT_EQ(self_found, self_expected) << count;
    EXPECT_EQ(self_meetings, static_cast<int>(self_expected.size())) << count;
    EXPECT_EQ(cross_found, cross_expected) << count;
  }
  EXPECT_GT(self_expected.size(), 100u);
  EXPECT_GT(cross_expected.size(), 50u);
}

TEST(Bvh, PairsBetweenTreesAndBoxQueriesMatchBruteForce) {
  std::mt19937 rng(6);
  auto a = random_boxes(rng, 300, 1.0), b = random_boxes(rng, 200, 1.0);
  Bvh ta(a), tb(b);
  std::set<std::pair<int, int>> found, expected;
  ta.pairs_with(tb, [&](int32_t i, int32_t j) { EXPECT_TRUE(found.emplace(i, j).second); });
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (a[i].overlaps(b[j])) expected.emplace(static_cast<int>(i), static_cast<int>(j));
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected.size(), 10u);
  Aabb q;
  q.grow(Vec3(-0.3, -0.3, -0.3));
  q.grow(Vec3(0.3, 0.3, 0.3));
  EXPECT_EQ(queried(ta, q), brute_query(a, q));
}

// A tree large enough to be built and refit in two halves side by side is the one-thread tree:
// the same pairs met in the same order, the same root box and looseness, before and after a refit.
TEST(Bvh, TwoThreadsBuildAndRefitTheOneThreadTree) {
  std::mt19937 rng(17);
  std::vector<Aabb> boxes = random_boxes(rng, 5000, 3.0);
  Bvh one(boxes, 1), two(boxes, 2);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::pair<int32_t, int32_t>> met_one, met_two;
    one.self_pairs([&](int32_t i, int32_t j) { met_one.emplace_back(i, j); });
    two.self_pairs([&](int32_t i, int32_t j) { met_two.emplace_back(i, j); });
    EXPECT_FALSE(met_one.empty());
    EXPECT_EQ(met_one, met_two) << "pass " << pass;
    EXPECT_EQ(one.subtrees(16), two.subtrees(16));
    EXPECT_EQ(one.leaves(), two.leaves());
    EXPECT_EQ(one.root_box().lo, two.root_box().lo);
    EXPECT_EQ(one.root_box().hi, two.root_box().hi);
    EXPECT_EQ(one.looseness(), two.looseness()) << "pass " << pass;
    for (auto& b : boxes) {  // drift, one side more than the other
      const Vec3 d(0.2 * std::sin(b.lo.y() * 3), 0.1 * b.lo.x(), 0.0);
      b.lo += d;
      b.hi += d;
    }
    one.refit(boxes, 1);
    two.refit(boxes, 2);
  }
}

// Looseness is the nodes' surface area over the primitives': two unit cubes a unit apart make a
// root of 3 x 1 x 1 (half area 7) over primitives of half area 3 each.
TEST(Bvh, LoosenessIsNodeAreaOverPrimitiveArea) {
  Aabb a, b;
  a.grow(Vec3(0, 0, 0));
  a.grow(Vec3(1, 1, 1));
  b.grow(Vec3(2, 0, 0));
  b.grow(Vec3(3, 1, 1));
  EXPECT_DOUBLE_EQ(Bvh({a, b}).looseness(), 7.0 / 6.0);
}

// A kept hierarchy refits while its boxes drift and is rebuilt once they have scattered (every
// box moved to another's place), so it is never looser than the bound over a fresh build, and
// its queries stay exact throughout.
TEST(Bvh, KeptHierarchyIsRebuiltWhenRefitsLoosenIt) {
  std::mt19937 rng(3);
  std::vector<Aabb> boxes = random_boxes(rng, 300, 1.0);
  const double bound = 1.2;
  RefitBvh kept(bound);
  std::vector<int> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  for (int update = 0; update < 6; ++update) {
    if (update == 3) {  // scatter: box i takes the place of box order[i]
      std::shuffle(order.begin(), order.end(), rng);
      std::vector<Aabb> moved(boxes.size());
      for (std::size_t i = 0; i < boxes.size(); ++i) moved[i] = boxes[static_cast<std::size_t>(order[i])];
      boxes = moved;
    } else {
      for (auto& b : boxes) {  // drift a little
        const Vec3 d(0.01 * std::sin(b.lo.y() * 3), 0.01, 0.0);
        b.lo += d;
        b.hi += d;
      }
    }
    const Bvh& tree = kept.update(boxes);
    EXPECT_LE(tree.looseness(), bound * Bvh(boxes).looseness() + 1e-12) << "update " << update;
    std::set<std::pair<int, int>> found;
    tree.self_pairs([&](int32_t i, int32_t j) { found.emplace(i, j); });
    EXPECT_EQ(found, brute_self(boxes)) << "update " << update;
  }
}

// A hierarchy over points (an obstacle's vertices) follows another's rebuilds, never its own
// looseness: update_with refits it in place, whatever the points did, unless told to rebuild,
// and its queries stay exact either way; `rebuilt` says which happened, for update too.
TEST(Bvh, KeptHierarchyOfPointsIsRebuiltOnlyWhenTold) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Aabb> points(200);
  auto scatter = [&] {
    for (auto& p : points) {
      p = Aabb();
      p.grow(Vec3(U(rng), U(rng), U(rng)));
    }
  };
  auto exact = [&](const Bvh& tree) {
    Aabb probe;
    probe.grow(Vec3(-0.5, -0.4, -0.5));
    probe.grow(Vec3(0.5, 0.6, 0.5));
    const std::set<int> brute = brute_query(points, probe);
    EXPECT_GT(brute.size(), 10u);
    EXPECT_EQ(queried(tree, probe), brute);
  };
  scatter();
  RefitBvh kept;
  const Bvh* first = &kept.update_with(points, false);
  EXPECT_TRUE(kept.rebuilt());  // nothing to refit yet
  scatter();
  const Bvh& refit = kept.update_with(points, false);
  EXPECT_FALSE(kept.rebuilt());
  EXPECT_EQ(&refit, first);
  exact(refit);
  kept.update_with(points, true);
  EXPECT_TRUE(kept.rebuilt());
  exact(kept.update_with(points, false));
  std::vector<Aabb> fewer(points.begin(), points.begin() + 100);
  kept.update_with(fewer, false);
  EXPECT_TRUE(kept.rebuilt());  // another number of primitives
  RefitBvh boxes;
  std::vector<Aabb> drifting = random_boxes(rng, 100, 1.0);
  boxes.update(drifting);
  EXPECT_TRUE(boxes.rebuilt());
  boxes.update(drifting);
  EXPECT_FALSE(boxes.rebuilt());
}

}  // namespace
}  // namespace vdc
