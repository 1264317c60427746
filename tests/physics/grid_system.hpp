// Test systems with the pattern of a sheet's: a grid graph's Laplacian with 3 unknowns a node,
// shifted to be positive definite.
#pragma once
#include <utility>
#include <vector>

#include "physics/assembly.hpp"

namespace vdc {

// Triplets of the grid system of side x side nodes, its unknowns numbered from `first`.
inline void add_grid_system(std::vector<Eigen::Triplet<double>>& t, int side, int first = 0) {
  auto node = [&](int i, int j) { return i * side + j; };
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int c = 0; c < 3; ++c) {
        const int r = first + 3 * node(i, j) + c;
        t.emplace_back(r, r, 6.1 + 0.01 * c);  // 6 neighbours: diagonally dominant
        for (const auto& [di, dj] : {std::pair{1, 0}, {0, 1}, {1, 1}}) {
          if (i + di >= side || j + dj >= side) continue;
          const int s = first + 3 * node(i + di, j + dj) + c;
          t.emplace_back(r, s, -1.0);
          t.emplace_back(s, r, -1.0);
        }
      }
}

inline SparseMatrix grid_system(int side) {
  std::vector<Eigen::Triplet<double>> t;
  add_grid_system(t, side);
  SparseMatrix a(3 * side * side, 3 * side * side);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace vdc
