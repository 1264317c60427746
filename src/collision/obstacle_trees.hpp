// An obstacle's vertex, face and edge hierarchies for collision detection (Bridson et al. 2002,
// section 7.1: boxes over a step's sweep), refit from its vertices' boxes, and kept between queries: a
// query at the positions where the last refit's sweep ended (the next step's proximity search
// after this step's continuous detection) takes the hierarchies as they are, since every swept
// box holds its end positions. Only the candidates change, never the pairs found.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"
#include "core/math.hpp"

namespace vdc {

class ObstacleTrees {
 public:
  // Refits to the vertices' paths from `start` to `end` (same sizes), each box padded by `pad`.
  void sweep(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<std::array<int32_t, 2>>& edges,
             const std::vector<Vec3>& start, const std::vector<Vec3>& end, double pad, int threads);
  // Hierarchies whose boxes hold the vertices at `x`: the face and edge hierarchies as they are
  // when the last sweep ended at x, else refit to x; the vertex hierarchy over the points x.
  void hold(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<std::array<int32_t, 2>>& edges,
            const std::vector<Vec3>& x, int threads);

  const Bvh& vertices() const { return *vertices_; }
  const Bvh& faces() const { return *faces_; }
  const Bvh& edges() const { return *edges_; }

 private:
  RefitBvh vertex_tree_, face_tree_, edge_tree_;
  const Bvh* vertices_ = nullptr;
  const Bvh* faces_ = nullptr;
  const Bvh* edges_ = nullptr;
  std::vector<Vec3> held_;  // where the last refit's sweep ended
  bool vertices_at_points_ = false;  // the vertex hierarchy's boxes are the points held_
};

}  // namespace vdc
