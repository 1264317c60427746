// Remeshing that does not make cloth cross cloth: a flip or a collapse changes the surface, and
// one whose new faces intersect more faces of the garment, or of the garments beside it, than the
// faces it removes did is refused. The count is the one untangling (Volino and Magnenat-Thalmann
// 2006) works on: intersecting pairs of faces that share no node.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "core/bvh.hpp"
#include "core/mesh.hpp"
#include "remesh/operations.hpp"

namespace vdc {

// What the garments being remeshed must not cross, as it stands at the frame's start: the
// obstacles' faces and every garment's, with the garment each belongs to (-1: an obstacle). Built
// once a frame and shared by the garments remeshed side by side.
struct StandingSurfaces {
  // `threads`: for building the hierarchy.
  StandingSurfaces(std::vector<Triangle> triangles, std::vector<int> owners, int threads = 1);
  std::vector<Triangle> triangles;
  std::vector<int> owners;
  Bvh tree;
};

class CrossingGuard {
 public:
  // `mesh` is garment `self` of `standing`, being remeshed: its own faces are looked at as they
  // change, those of the others in `standing` as they stood.
  CrossingGuard(const Mesh& mesh, const StandingSurfaces& standing, int self);
  CrossingGuard(const CrossingGuard&) = delete;
  CrossingGuard& operator=(const CrossingGuard&) = delete;

  // The faces an operation made join the guarded surface (the faces it removed leave it).
  void add(const OpRecord& done);
  // True when the operation previewed would leave more intersecting pairs than there are.
  bool adds_crossings(const OpPreview& op);
  // Operations refused so far.
  int refused() const { return refused_; }

 private:
  // Intersecting pairs of triangle t (nodes `nodes`) with the guarded faces other than `skip`.
  int crossings_of(const Triangle& t, const std::array<NodeId, 3>& nodes, const std::vector<FaceId>& skip);
  Triangle triangle(FaceId f) const;
  void reindex();  // builds the tree over the garment's live faces

  const Mesh& mesh_;
  const StandingSurfaces& standing_;
  int self_;
  std::vector<FaceId> indexed_;   // the garment's faces in own_tree_, in its leaf order
  std::unique_ptr<Bvh> own_tree_;
  std::vector<FaceId> recent_;    // faces made since the tree was built, searched one by one
  std::vector<Aabb> recent_boxes_;
  int refused_ = 0;
};

}  // namespace vdc
