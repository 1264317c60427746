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

using Triangle = std::array<Vec3, 3>;

class CrossingGuard {
 public:
  // `mesh` is the garment being remeshed, its faces as they stand; `neighbours` the faces of the
  // garments it may touch, fixed while it is remeshed.
  CrossingGuard(const Mesh& mesh, std::vector<Triangle> neighbours);
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
  std::vector<Triangle> neighbours_;
  Bvh neighbour_tree_;
  std::vector<FaceId> indexed_;   // the garment's faces in own_tree_, in its leaf order
  std::unique_ptr<Bvh> own_tree_;
  std::vector<FaceId> recent_;    // faces made since the tree was built, searched one by one
  std::vector<Aabb> recent_boxes_;
  int refused_ = 0;
};

}  // namespace vdc
