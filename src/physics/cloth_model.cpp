#include "physics/cloth_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vdc {

namespace {

BendStencil stencil(const Mesh& mesh, EdgeId e) {
  return {mesh.x(mesh.edge_node(e, 0)), mesh.x(mesh.edge_node(e, 1)), mesh.x(mesh.opposite_node(e, 0)),
          mesh.x(mesh.opposite_node(e, 1))};
}

// The mesh's kCompressionAttr, or null where it has none (every factor 1).
const Attribute<FaceTag, double>* compression_factors(const Mesh& mesh) {
  return mesh.face_attrs().has(kCompressionAttr) ? &mesh.face_attrs().get<double>(kCompressionAttr) : nullptr;
}

// The element's compression factor, and its gathered strain with `gathering` where the mesh
// has one.
void set_compression(MembraneElement& m, FaceId f, const Attribute<FaceTag, double>* compression,
                     const Attribute<FaceTag, Vec2>* gathered, double gathering) {
  m.compression = compression ? (*compression)[f] : 1.0;
  if (gathered == nullptr || !(gathering > 0)) return;
  m.gathered = (*gathered)[f];
  m.gathering = gathering;
}

const Attribute<FaceTag, Vec2>* gathered_strains(const Mesh& mesh) {
  return mesh.face_attrs().has(kGatheredAttr) ? &mesh.face_attrs().get<Vec2>(kGatheredAttr) : nullptr;
}

}  // namespace

int32_t append_garment(ClothModel& model, const Mesh& mesh, const Material& material, double gathering) {
  if (!mesh.is_compact()) throw std::logic_error("append_garment needs a compact mesh");
  const int32_t offset = model.num_nodes;
  model.num_nodes += mesh.num_nodes();
  model.node_mass.resize(static_cast<std::size_t>(model.num_nodes), 0.0);
  const MembraneStiffness k = material.membrane();
  const auto* compression = compression_factors(mesh);
  const auto* gathered = gathered_strains(mesh);
  for (FaceId f : mesh.faces()) {
    const auto& vs = mesh.face_verts(f);
    MembraneElement m = make_membrane_element(mesh.u(vs[0]), mesh.u(vs[1]), mesh.u(vs[2]), k);
    set_compression(m, f, compression, gathered, gathering);
    std::array<int32_t, 3> nodes{};
    for (int i = 0; i < 3; ++i) {
      nodes[static_cast<std::size_t>(i)] = offset + mesh.face_node(f, i).idx;
      model.node_mass[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])] += material.density * m.area / 3.0;
    }
    model.face_nodes.push_back(nodes);
    model.membranes.push_back(m);
  }
  const Attribute<EdgeTag, double>* rest =
      mesh.edge_attrs().has(kRestAngleAttr) ? &mesh.edge_attrs().get<double>(kRestAngleAttr) : nullptr;
  for (EdgeId e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    // On a seam the two sides may differ in rest length: use their mean.
    double len = 0.5 * ((mesh.u(mesh.edge_vert(e, 0, 1)) - mesh.u(mesh.edge_vert(e, 0, 0))).norm() +
                        (mesh.u(mesh.edge_vert(e, 1, 1)) - mesh.u(mesh.edge_vert(e, 1, 0))).norm());
    BendingElement b;
    b.coeff = bending_coefficient(material.bending, len, mesh.material_area(mesh.edge_face(e, 0)),
                                  mesh.material_area(mesh.edge_face(e, 1)));
    b.theta0 = rest ? (*rest)[e] : 0.0;
    model.bend_nodes.push_back({offset + mesh.edge_node(e, 0).idx, offset + mesh.edge_node(e, 1).idx,
                                offset + mesh.opposite_node(e, 0).idx, offset + mesh.opposite_node(e, 1).idx});
    model.bends.push_back(b);
  }
  return offset;
}

void update_compression(ClothModel& model, const Mesh& mesh, std::size_t first_face, double gathering) {
  const auto* compression = compression_factors(mesh);
  const auto* gathered = gathered_strains(mesh);
  std::size_t i = first_face;
  for (FaceId f : mesh.faces()) set_compression(model.membranes.at(i++), f, compression, gathered, gathering);
}

void record_gathering(Mesh& mesh, const char* unbound_attr) {
  if (!mesh.face_attrs().has(kCompressionAttr)) return;
  const auto& compression = mesh.face_attrs().get<double>(kCompressionAttr);
  auto& gathered = mesh.face_attrs().get_or_add<Vec2>(kGatheredAttr, Vec2::Zero());
  auto& recorded_area = mesh.face_attrs().get_or_add<double>(kGatheredAreaAttr, 0.0);
  const auto* unbound =
      unbound_attr != nullptr && mesh.face_attrs().has(unbound_attr) ? &mesh.face_attrs().get<double>(unbound_attr) : nullptr;
  const double no_limit = -std::numeric_limits<double>::infinity();
  for (FaceId f : mesh.faces()) {
    if (!(compression[f] < 1)) {
      gathered[f] = Vec2::Zero();
      recorded_area[f] = 0;
      continue;
    }
    if (unbound != nullptr && (*unbound)[f] > 0) {
      gathered[f] = Vec2(no_limit, no_limit);
      recorded_area[f] = 0;
      continue;
    }
    const auto& vs = mesh.face_verts(f);
    const MembraneElement m = make_membrane_element(mesh.u(vs[0]), mesh.u(vs[1]), mesh.u(vs[2]), MembraneStiffness{});
    if (std::abs(recorded_area[f] - m.area) <= 1e-9 * m.area) continue;
    const Mat2 e = green_strain(deformation_gradient({mesh.x(mesh.face_node(f, 0)), mesh.x(mesh.face_node(f, 1)), mesh.x(mesh.face_node(f, 2))}, m));
    gathered[f] = Vec2(std::min(e(0, 0), 0.0), std::min(e(1, 1), 0.0));
    recorded_area[f] = m.area;
  }
}

void set_rest_angles_from_world(Mesh& mesh) {
  auto& rest = mesh.edge_attrs().get_or_add<double>(kRestAngleAttr, 0.0);
  for (EdgeId e : mesh.edges()) rest[e] = mesh.is_boundary(e) ? 0.0 : dihedral_angle(stencil(mesh, e));
}

}  // namespace vdc
