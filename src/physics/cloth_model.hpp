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

// Name of the optional face attribute (Vec2) holding the warp and weft strain a coarse face was
// made with (membrane.hpp's `gathered`), and of the one (double) holding the material area it
// was recorded on: a face the remesher made since covers other material (a split or a collapse)
// and records its own; a flip that keeps the area covers the same cloth and keeps the record.
inline constexpr const char* kGatheredAttr = "gathered";
inline constexpr const char* kGatheredAreaAttr = "gathered_area";

// Appends a compact mesh's elements; its node i becomes model node offset + i. Returns the offset.
// With `gathering` > 0 its membranes resist gathering beyond the mesh's kGatheredAttr with that
// factor (membrane.hpp).
int32_t append_garment(ClothModel& model, const Mesh& mesh, const Material& material, double gathering = 0);

// Sets the membranes' compression factors (and, with `gathering` > 0, their gathered strains) of
// the garment whose faces start at model face `first_face` from its mesh's kCompressionAttr (1
// where absent) and kGatheredAttr, without rebuilding anything.
void update_compression(ClothModel& model, const Mesh& mesh, std::size_t first_face, double gathering = 0);

// Records kGatheredAttr on every face whose compression factor is below 1 and that has none for
// its material area yet (coarsened, split or collapsed since the last call): its compressive
// warp and weft Green strain now (0 where stretched). A face at factor 1 forgets it. Faces that
// keep their material keep what they were made with. Faces where the double face attribute
// named `unbound_attr` (when given and present) is above 0 keep no memory (-infinity: the
// compression factor alone, however far they gather).
void record_gathering(Mesh& mesh, const char* unbound_attr = nullptr);

// Sets the edge attribute kRestAngleAttr to the current dihedral angles (a garment whose rest
// shape is its initial world shape).
void set_rest_angles_from_world(Mesh& mesh);

}  // namespace vdc
