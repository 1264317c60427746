// The cloth model takes each face's membrane compression factor from the mesh's face attribute,
// in the garment's own place among the model's elements, when built and when updated in place.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/mesh_build.hpp"
#include "physics/cloth_model.hpp"
#include "remesh/operations.hpp"

namespace vdc {
namespace {

TEST(ClothModel, MembranesTakeEachFacesCompressionWhenBuiltAndWhenUpdated) {
  Mesh first = build_mesh(make_grid(0.2, 0.2, 2, 2));
  Mesh second = build_mesh(make_grid(0.3, 0.1, 3, 1));
  auto& factor = second.face_attrs().get_or_add<double>(kCompressionAttr, 1.0);
  double value = 0.9;
  for (FaceId f : second.faces()) factor[f] = value -= 0.1;  // 0.8, 0.7, ...: one for each face

  ClothModel model;
  append_garment(model, first, Material());
  const std::size_t first_face = model.membranes.size();
  append_garment(model, second, Material());
  ASSERT_EQ(model.membranes.size(), first_face + static_cast<std::size_t>(second.num_faces()));
  // The first garment has no attribute: the plain material.
  for (std::size_t i = 0; i < first_face; ++i) EXPECT_EQ(model.membranes[i].compression, 1.0);
  std::size_t i = first_face;
  for (FaceId f : second.faces()) EXPECT_EQ(model.membranes[i++].compression, factor[f]);

  // Changed on the mesh, set on the elements in place; the first garment's are untouched.
  for (FaceId f : second.faces()) factor[f] = 0.5 * factor[f];
  update_compression(model, second, first_face);
  for (std::size_t k = 0; k < first_face; ++k) EXPECT_EQ(model.membranes[k].compression, 1.0);
  i = first_face;
  for (FaceId f : second.faces()) EXPECT_EQ(model.membranes[i++].compression, factor[f]);
  EXPECT_DOUBLE_EQ(model.membranes[first_face].compression, 0.4);
}

// A sheet squeezed along warp to 0.9 (E11 = -0.095, weft unstrained): its coarse faces record
// that gathering, the others none; squeezed further to 0.8 the faces keep what they were made
// with, so do the two faces of a square cell whose diagonal is flipped (the same cloth), a face
// split since records its own (E11 = -0.18), a face back at factor 1 forgets; the model carries
// the record with the gathering factor, and ignores it without one.
TEST(ClothModel, CoarseFacesRecordTheGatheringTheyWereMadeWith) {
  Mesh mesh = build_mesh(make_grid(0.2, 0.2, 2, 2));
  auto& factor = mesh.face_attrs().get_or_add<double>(kCompressionAttr, 1.0);
  std::vector<FaceId> faces;
  for (FaceId f : mesh.faces()) faces.push_back(f);
  const FaceId coarse = faces[0], fine = faces[1], later = faces[2];
  for (FaceId f : faces) factor[f] = f == fine ? 1.0 : 0.25;
  const auto squeeze = [&mesh](double s) {
    for (NodeId n : mesh.nodes()) mesh.x(n).x() = s * mesh.u(mesh.node_verts(n).front()).x();
  };
  squeeze(0.9);
  record_gathering(mesh);
  const auto& gathered = mesh.face_attrs().get<Vec2>(kGatheredAttr);
  const double made = 0.5 * (0.9 * 0.9 - 1);
  EXPECT_NEAR(gathered[coarse].x(), made, 1e-14);
  EXPECT_EQ(gathered[coarse].y(), 0.0);
  EXPECT_EQ(gathered[fine], Vec2::Zero());

  squeeze(0.8);
  factor[later] = 1.0;
  record_gathering(mesh);
  EXPECT_NEAR(gathered[coarse].x(), made, 1e-14);  // the same triangle: what it was made with
  EXPECT_EQ(gathered[later], Vec2::Zero());         // back at factor 1: forgotten
  // A cell's diagonal between two coarse faces, flipped: the same cloth, the same record.
  EdgeId diagonal;
  for (EdgeId e : mesh.edges()) {
    const Vec2 du = mesh.u(mesh.edge_vert(e, 0, 1)) - mesh.u(mesh.edge_vert(e, 0, 0));
    if (mesh.is_boundary(e) || std::abs(du.norm() - 0.1 * std::sqrt(2.0)) > 1e-12) continue;
    if (factor[mesh.edge_face(e, 0)] < 1 && factor[mesh.edge_face(e, 1)] < 1 && mesh.edge_face(e, 0) != coarse &&
        mesh.edge_face(e, 1) != coarse)
      diagonal = e;
  }
  ASSERT_TRUE(diagonal.valid());
  const OpRecord flipped = flip_edge(mesh, diagonal);
  ASSERT_EQ(flipped.added_faces.size(), 2u);
  record_gathering(mesh);
  for (FaceId f : flipped.added_faces) EXPECT_NEAR(mesh.face_attrs().get<Vec2>(kGatheredAttr)[f].x(), made, 1e-14);
  // A split face (coarse, its parent's attributes copied) records its own triangle's strain.
  EdgeId edge;
  for (EdgeId e : mesh.face_edges(coarse))
    if (!mesh.is_boundary(e)) edge = e;
  ASSERT_TRUE(edge.valid());
  const OpRecord rec = split_edge(mesh, edge);
  squeeze(0.8);  // the new node on the squeezed sheet too
  record_gathering(mesh);
  const auto& after = mesh.face_attrs().get<Vec2>(kGatheredAttr);
  int recorded = 0;
  for (FaceId f : rec.added_faces)
    if (mesh.face_attrs().get<double>(kCompressionAttr)[f] < 1) {
      EXPECT_NEAR(after[f].x(), 0.5 * (0.8 * 0.8 - 1), 1e-14);
      ++recorded;
    }
  EXPECT_GE(recorded, 2);

  mesh.compact();
  ClothModel with, without;
  append_garment(with, mesh, Material(), 0.3);
  append_garment(without, mesh, Material());
  std::size_t i = 0;
  const auto& compact = mesh.face_attrs().get<Vec2>(kGatheredAttr);
  for (FaceId f : mesh.faces()) {
    EXPECT_EQ(with.membranes[i].gathered, compact[f]);
    EXPECT_EQ(with.membranes[i].gathering, 0.3);
    EXPECT_EQ(without.membranes[i].gathering, 0.0);
    ++i;
  }
  update_compression(without, mesh, 0, 0.3);
  EXPECT_EQ(without.membranes[0].gathering, 0.3);
  EXPECT_EQ(without.membranes[0].gathered, compact[*mesh.faces().begin()]);
}

// Faces marked free (here by an attribute of the caller's, as the simulation marks the faces
// the folds too fine for the image coarsened) keep no memory: squeezed past what they were
// made with (warp 0.9, then 0.8), a free face answers with the compression factor alone, a
// recorded one with (0.25 * -0.095 + 0.3 * -0.085)^2 / (0.25 * -0.18)^2 = 1.2 times the energy.
TEST(ClothModel, FacesLeftFreeKeepNoMemoryOfTheirGathering) {
  Mesh mesh = build_mesh(make_grid(0.2, 0.2, 2, 2));
  auto& factor = mesh.face_attrs().get_or_add<double>(kCompressionAttr, 1.0);
  auto& free = mesh.face_attrs().get_or_add<double>("free_faces", 0.0);
  const FaceId loose = *mesh.faces().begin();
  for (FaceId f : mesh.faces()) factor[f] = 0.25;
  free[loose] = 1;
  for (NodeId n : mesh.nodes()) mesh.x(n).x() = 0.9 * mesh.u(mesh.node_verts(n).front()).x();
  record_gathering(mesh, "free_faces");
  const auto& gathered = mesh.face_attrs().get<Vec2>(kGatheredAttr);
  EXPECT_EQ(gathered[loose].x(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(gathered[loose].y(), -std::numeric_limits<double>::infinity());
  FaceId held;
  for (FaceId f : mesh.faces())
    if (f != loose) held = f;
  EXPECT_NEAR(gathered[held].x(), 0.5 * (0.9 * 0.9 - 1), 1e-14);

  ClothModel with, without;
  append_garment(with, mesh, Material(), 0.3);
  append_garment(without, mesh, Material());
  const auto stencil = [&mesh](FaceId f, double s) {
    TriStencil x;
    for (int i = 0; i < 3; ++i) x[static_cast<std::size_t>(i)] = Vec3(s * mesh.u(mesh.face_vert(f, i)).x(), 0, -mesh.u(mesh.face_vert(f, i)).y());
    return x;
  };
  const std::size_t a = static_cast<std::size_t>(loose.idx), b = static_cast<std::size_t>(held.idx);
  EXPECT_EQ(membrane_energy(stencil(loose, 0.8), with.membranes[a]), membrane_energy(stencil(loose, 0.8), without.membranes[a]));
  EXPECT_GT(membrane_energy(stencil(held, 0.8), with.membranes[b]), 1.15 * membrane_energy(stencil(held, 0.8), without.membranes[b]));
}

}  // namespace
}  // namespace vdc
