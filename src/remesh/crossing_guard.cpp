// Flips and collapses refused where they would make cloth cross cloth (the crossing count of
// Volino and Magnenat-Thalmann 2006, kept from rising while remeshing, Narain et al. 2012 sec. 4).
#include "remesh/crossing_guard.hpp"

#include <algorithm>

#include "collision/intersection.hpp"

namespace vdc {

namespace {

// Faces made that are searched one by one before they go into a tree.
constexpr std::size_t kTail = 32;

Aabb box_of(const Triangle& t) {
  Aabb b;
  for (const Vec3& p : t) b.grow(p);
  return b;
}

std::vector<Aabb> boxes_of(const std::vector<Triangle>& triangles) {
  std::vector<Aabb> boxes;
  boxes.reserve(triangles.size());
  for (const Triangle& t : triangles) boxes.push_back(box_of(t));
  return boxes;
}

bool shares_node(const Mesh& mesh, FaceId f, const std::array<NodeId, 3>& nodes) {
  for (int k = 0; k < 3; ++k) {
    const NodeId n = mesh.face_node(f, k);
    if (n == nodes[0] || n == nodes[1] || n == nodes[2]) return true;
  }
  return false;
}

}  // namespace

StandingSurfaces::StandingSurfaces(std::vector<Triangle> t, std::vector<int> o, int threads)
    : triangles(std::move(t)), owners(std::move(o)), tree(boxes_of(triangles), threads) {}

CrossingGuard::CrossingGuard(const Mesh& mesh, const StandingSurfaces& standing, int self)
    : mesh_(mesh), standing_(standing), self_(self) {
  reindex();
}

void CrossingGuard::reindex() {
  indexed_.clear();
  std::vector<Triangle> triangles;
  for (FaceId f : mesh_.faces()) {
    indexed_.push_back(f);
    triangles.push_back(triangle(f));
  }
  own_tree_ = std::make_unique<Bvh>(boxes_of(triangles));
  indexed_below_ = mesh_.face_capacity();
  indexed_dead_ = 0;
  list_ = Made{};
  levels_.clear();
}

Triangle CrossingGuard::triangle(FaceId f) const {
  return {mesh_.x(mesh_.face_node(f, 0)), mesh_.x(mesh_.face_node(f, 1)), mesh_.x(mesh_.face_node(f, 2))};
}

void CrossingGuard::add(const OpRecord& done) {
  for (FaceId f : done.removed_faces)
    if (f.idx < indexed_below_) ++indexed_dead_;
  // Coarsening removes most of the faces the tree was built over: once half are gone, searching
  // past them costs more than a new tree.
  if (2 * indexed_dead_ > indexed_.size()) {
    reindex();
    return;
  }
  for (FaceId f : done.added_faces) {
    list_.faces.push_back(f);
    list_.boxes.push_back(box_of(triangle(f)));
  }
  if (list_.faces.size() >= kTail) carry();
}

void CrossingGuard::carry() {
  // Faces removed since they were made leave as their level is rebuilt (face ids are not reused
  // before the mesh is compacted, so a dead face is never met again).
  Made carried;
  auto take_live = [&](const Made& from) {
    for (std::size_t i = 0; i < from.faces.size(); ++i)
      if (mesh_.alive(from.faces[i])) {
        carried.faces.push_back(from.faces[i]);
        carried.boxes.push_back(from.boxes[i]);
      }
  };
  take_live(list_);
  list_ = Made{};
  std::size_t k = 0;
  for (; k < levels_.size() && levels_[k].tree; ++k) {
    take_live(levels_[k]);
    levels_[k] = Made{};
  }
  if (k == levels_.size()) levels_.emplace_back();
  carried.tree = std::make_unique<Bvh>(carried.boxes);
  levels_[k] = std::move(carried);
}

int CrossingGuard::crossings_of(const Triangle& t, const std::array<NodeId, 3>& nodes, const std::vector<FaceId>& skip) {
  const Aabb box = box_of(t);
  // Boxes wholly on one side of t's plane hold no triangle that t crosses (triangles_intersect
  // would reject each by that plane).
  const PlaneOf plane(t);
  auto near = [&](const Aabb& b) { return b.overlaps(box) && !plane.clears(b); };
  int count = 0;
  auto test_own = [&](FaceId f) {
    if (!mesh_.alive(f) || shares_node(mesh_, f, nodes) || std::find(skip.begin(), skip.end(), f) != skip.end()) return;
    if (triangles_intersect(t, triangle(f))) ++count;
  };
  own_tree_->query_if(near, [&](int32_t i) { test_own(indexed_[static_cast<std::size_t>(i)]); });
  for (const Made& level : levels_)
    if (level.tree) level.tree->query_if(near, [&](int32_t i) { test_own(level.faces[static_cast<std::size_t>(i)]); });
  for (std::size_t i = 0; i < list_.faces.size(); ++i)
    if (near(list_.boxes[i])) test_own(list_.faces[i]);
  standing_.tree.query_if(near, [&](int32_t i) {
    const auto k = static_cast<std::size_t>(i);
    if (standing_.owners[k] != self_ && triangles_intersect(t, standing_.triangles[k])) ++count;
  });
  return count;
}

bool CrossingGuard::adds_crossings(const OpPreview& op) {
  int made = 0;
  for (const auto& nodes : op.made) made += crossings_of({mesh_.x(nodes[0]), mesh_.x(nodes[1]), mesh_.x(nodes[2])}, nodes, op.removed);
  if (made == 0) return false;
  int removed = 0;
  for (FaceId f : op.removed)
    removed += crossings_of(triangle(f), {mesh_.face_node(f, 0), mesh_.face_node(f, 1), mesh_.face_node(f, 2)}, op.removed);
  if (made <= removed) return false;
  ++refused_;
  return true;
}

}  // namespace vdc
