// Procedural garments: the dress is a valid two-space mesh whose seams are closed, free of
// self-intersections, and placed around the figure's body in its rest pose without touching it.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/distance.hpp"
#include "collision/intersection.hpp"
#include "core/bvh.hpp"
#include "scene/body.hpp"
#include "scene/figure.hpp"
#include "scene/garments.hpp"
#include "support/triangle_soup.hpp"

namespace vdc {
namespace {

TEST(Garments, DressIsSewnClosedAndClearOfTheBody) {
  const DressParams params;
  const MeshSource src = make_dress(params);
  const Mesh dress = build_mesh(src);  // manifold, consistently oriented, counter-clockwise patterns
  ASSERT_TRUE(dress.validate().ok());

  // Open edges: the hem, the top edge outside the straps' ends, and the straps' long sides.
  int boundary = 0, seam_nodes = 0;
  for (EdgeId e : dress.edges()) boundary += dress.is_boundary(e);
  for (NodeId v : dress.nodes()) seam_nodes += dress.node_verts(v).size() > 1;
  int strap_sides = 0;
  for (EdgeId e : dress.edges())
    if (dress.is_boundary(e) && dress.x(dress.edge_node(e, 0)).y() > params.top_height + 1e-9) ++strap_sides;
  EXPECT_EQ(boundary, params.around + (params.around - 8) + strap_sides + 4);  // + the strap sides' end segments
  EXPECT_GT(strap_sides, 0);
  // Seam nodes: the back seams of bodice and skirt, the waist, three at each strap end.
  const int rows_bodice = static_cast<int>(std::round((params.top_height - params.waist_height) / params.cell));
  const int rows_skirt =
      static_cast<int>(std::round(std::hypot(params.waist_height - params.hem_height, params.hem_radius - params.bodice_radius) / params.cell));
  EXPECT_EQ(seam_nodes, (rows_bodice + 1) + rows_skirt + (params.around - 1) + 12);

  const test::TriangleSoup soup = test::triangle_soup(dress);
  EXPECT_EQ(count_self_intersections(soup.faces, soup.x), 0);

  // The figure's body in its rest pose: no dress vertex within 5 mm of it, no face through it.
  Motion rest;
  rest.skeleton = figure_skeleton();
  rest.frames.assign(1, std::vector<double>(static_cast<std::size_t>(rest.skeleton.num_channels), 0.0));
  const Body body(rest, BodyParams{});
  const MeshSource& b = body.rest_mesh();
  std::vector<Aabb> boxes(b.faces.size());
  for (std::size_t f = 0; f < b.faces.size(); ++f)
    for (const Corner& c : b.faces[f]) boxes[f].grow(b.positions[static_cast<std::size_t>(c.node)]);
  const Bvh tree(boxes);
  double closest = 1e9;
  for (NodeId v : dress.nodes()) {
    double best = 0.05;
    tree.nearest(dress.x(v), best, [&](int32_t f) {
      const auto& t = b.faces[static_cast<std::size_t>(f)];
      return point_triangle_distance(dress.x(v), b.positions[static_cast<std::size_t>(t[0].node)], b.positions[static_cast<std::size_t>(t[1].node)],
                                     b.positions[static_cast<std::size_t>(t[2].node)]);
    });
    closest = std::min(closest, best);
  }
  EXPECT_GT(closest, 0.005);
  std::vector<std::array<int32_t, 3>> body_faces;
  for (const auto& f : b.faces) body_faces.push_back({f[0].node, f[1].node, f[2].node});
  const int crossings = count_intersections_between(soup.faces, soup.x, body_faces, b.positions);
  EXPECT_EQ(crossings, 0);
  std::cout << "dress: " << dress.num_faces() << " faces, closest to the body " << closest * 1000 << " mm\n";
}

}  // namespace
}  // namespace vdc

namespace vdc {
namespace {

// A tube's pattern is its exact development: every face has the same edge lengths in material
// space as in the world, for a cone flaring down, a cone narrowing down and a cylinder.
TEST(Garments, TubePatternIsTheDevelopedTube) {
  for (const auto& [top_radius, bottom_radius] : {std::pair{0.2, 0.36}, std::pair{0.3, 0.2}, std::pair{0.23, 0.23}}) {
    TubeParams p;
    p.top_height = 1.0;
    p.top_radius = top_radius;
    p.bottom_height = 0.3;
    p.bottom_radius = bottom_radius;
    const Mesh tube = build_mesh(make_tube(p));
    ASSERT_TRUE(tube.validate().ok());
    double worst = 0;
    for (FaceId f : tube.faces())
      for (int i = 0; i < 3; ++i) {
        const double world = (tube.x(tube.face_node(f, i)) - tube.x(tube.face_node(f, (i + 1) % 3))).norm();
        const double material = (tube.u(tube.face_vert(f, i)) - tube.u(tube.face_vert(f, (i + 1) % 3))).norm();
        worst = std::max(worst, std::abs(world - material));
      }
    EXPECT_LT(worst, 1e-12) << top_radius << " to " << bottom_radius;
    // Two open rings and one back seam.
    int boundary = 0, seam_nodes = 0;
    for (EdgeId e : tube.edges()) boundary += tube.is_boundary(e);
    for (NodeId v : tube.nodes()) seam_nodes += tube.node_verts(v).size() > 1;
    const int rows = static_cast<int>(std::round(std::hypot(0.7, bottom_radius - top_radius) / p.cell));
    EXPECT_EQ(boundary, 2 * p.around);
    EXPECT_EQ(seam_nodes, rows + 1);
  }
}

}  // namespace
}  // namespace vdc
