// Meshes as the triangle soups the exact intersection tests (collision/intersection.hpp) take,
// and the crossings those tests count.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "collision/intersection.hpp"
#include "core/mesh.hpp"

namespace vdc::test {

struct TriangleSoup {
  std::vector<std::array<int32_t, 3>> faces;  // node indices
  std::vector<Vec3> x;                        // by node index (unused slots zero)
};

inline TriangleSoup triangle_soup(const Mesh& m) {
  TriangleSoup s;
  s.x.resize(static_cast<std::size_t>(m.node_capacity()), Vec3::Zero());
  for (NodeId n : m.nodes()) s.x[static_cast<std::size_t>(n.idx)] = m.x(n);
  for (FaceId f : m.faces()) s.faces.push_back({m.face_node(f, 0).idx, m.face_node(f, 1).idx, m.face_node(f, 2).idx});
  return s;
}

// Pairs of faces of `m` that cross each other.
inline int self_crossings(const Mesh& m) {
  const TriangleSoup s = triangle_soup(m);
  return count_self_intersections(s.faces, s.x);
}

// Pairs of a face of `a` and a face of `b` that cross.
inline int crossings_between(const Mesh& a, const Mesh& b) {
  const TriangleSoup sa = triangle_soup(a), sb = triangle_soup(b);
  return count_intersections_between(sa.faces, sa.x, sb.faces, sb.x);
}

}  // namespace vdc::test
