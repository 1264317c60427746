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
  // Faces made while remeshing, kept in the logarithmic method of Bentley and Saxe (1980): a
  // short list searched one by one, and trees over 2^k of those lists each, merged as a binary
  // counter carries, so a face is put into a tree about log(made / kTail) times and a search
  // meets one tree a level.
  struct Made {
    std::vector<FaceId> faces;
    std::vector<Aabb> boxes;
    std::unique_ptr<Bvh> tree;  // over `boxes`; none for the list
  };

  // Intersecting pairs of triangle t (nodes `nodes`) with the guarded faces other than `skip`.
  int crossings_of(const Triangle& t, const std::array<NodeId, 3>& nodes, const std::vector<FaceId>& skip);
  Triangle triangle(FaceId f) const;
  void carry();    // the full list into the levels' trees
  void reindex();  // one tree over every live face, the list and levels emptied

  const Mesh& mesh_;
  const StandingSurfaces& standing_;
  int self_;
  std::vector<FaceId> indexed_;   // the garment's faces when own_tree_ was built, in its primitive order
  std::unique_ptr<Bvh> own_tree_;
  int32_t indexed_below_ = 0;     // face ids below this were made before own_tree_
  std::size_t indexed_dead_ = 0;  // faces of own_tree_ removed since
  Made list_;                     // the latest faces made, at most kTail
  std::vector<Made> levels_;      // level k: about kTail 2^k faces made (fewer once dead ones drop out), or empty
  int refused_ = 0;
};

}  // namespace vdc
