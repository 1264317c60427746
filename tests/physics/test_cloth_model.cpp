// The cloth model takes each face's membrane compression factor from the mesh's face attribute,
// in the garment's own place among the model's elements, when built and when updated in place.
#include <gtest/gtest.h>

#include "core/mesh_build.hpp"
#include "physics/cloth_model.hpp"

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

}  // namespace
}  // namespace vdc
