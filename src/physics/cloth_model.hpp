// The elements of every garment in one system: membranes on faces, bending on interior edges,
// lumped node masses. Node indices are global: garment node + the garment's offset.
#pragma once
#include <array>
#include <vector>

#include "core/mesh.hpp"
#include "physics/bending.hpp"
#include "physics/material.hpp"
#include "physics/membrane.hpp"

namespace vdc {

struct ClothModel {
  int32_t num_nodes = 0;
  std::vector<double> node_mass;  // lumped: density * area / 3 from each face
  std::vector<std::array<int32_t, 3>> face_nodes;
  std::vector<MembraneElement> membranes;
  std::vector<std::array<int32_t, 4>> bend_nodes;  // edge 0, edge 1, opposite in face 0, in face 1
  std::vector<BendingElement> bends;
};

// Name of the optional edge attribute (double) holding bending rest angles; absent means flat.
inline constexpr const char* kRestAngleAttr = "rest_angle";

// Name of the optional face attribute (double) holding each face's membrane `compression` factor
// c (membrane.hpp: an element too coarse for its wrinkles keeps c^2 of its stiffness against
// warp and weft compression); absent means 1, the plain material.
inline constexpr const char* kCompressionAttr = "compression";

// Appends a compact mesh's elements; its node i becomes model node offset + i. Returns the offset.
int32_t append_garment(ClothModel& model, const Mesh& mesh, const Material& material);

// Sets the membranes' compression factors of the garment whose faces start at model face
// `first_face` from its mesh's kCompressionAttr (1 where absent), without rebuilding anything.
void update_compression(ClothModel& model, const Mesh& mesh, std::size_t first_face);

// Sets the edge attribute kRestAngleAttr to the current dihedral angles (a garment whose rest
// shape is its initial world shape).
void set_rest_angles_from_world(Mesh& mesh);

}  // namespace vdc
