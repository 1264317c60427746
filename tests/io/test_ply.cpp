// The view factors' PLY: what a run writes reads back (positions to the rounding asked for,
// faces, values to the 6 significant digits written, whole numbers exactly), and each malformed file is refused naming
// its line.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "core/mesh.hpp"
#include "core/mesh_build.hpp"
#include "io/ply.hpp"
#include "support/temp_file.hpp"
#include "support/text.hpp"

namespace vdc {
namespace {

using test::contains;
using test::TempFile;

TEST(PlyFaceValues, WhatARunWritesReadsBack) {
  Mesh m = build_mesh(make_grid(0.7, 1.3, 5, 4));
  auto& view = m.face_attrs().get_or_add<double>("view_factor", 1.0);
  int k = 0;
  for (FaceId f : m.faces()) view[f] = 1.0 / (1 + k++);  // 1, 0.5, 0.333333, ...
  TempFile tmp(".ply");
  auto& reason = m.face_attrs().get_or_add<double>("view_reason", 0.0);
  k = 0;
  for (FaceId f : m.faces()) reason[f] = k++ % 5;
  ASSERT_TRUE(write_ply_with_face_values(m, tmp.path(), {{"view", "view_factor"}, {"reason", "view_reason", true}}, 6));
  const PlyFaceValues ply = read_ply_with_face_values(tmp.path());
  EXPECT_EQ(ply.name, "view");
  ASSERT_EQ(ply.more.count("reason"), 1u);
  ASSERT_EQ(ply.more.at("reason").size(), static_cast<std::size_t>(m.num_faces()));
  ASSERT_EQ(ply.positions.size(), static_cast<std::size_t>(m.num_nodes()));
  int32_t n = 0;
  for (NodeId v : m.nodes()) EXPECT_LE((ply.positions[static_cast<std::size_t>(n++)] - m.x(v)).cwiseAbs().maxCoeff(), 0.5e-6 + 1e-15);
  ASSERT_EQ(ply.faces.size(), static_cast<std::size_t>(m.num_faces()));
  std::size_t i = 0;
  for (FaceId f : m.faces()) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(ply.faces[i][static_cast<std::size_t>(c)], m.face_node(f, c).idx) << i;
    EXPECT_NEAR(ply.values[i], view[f], 5e-6 * view[f]) << i;  // half a unit of the 6th digit
    EXPECT_EQ(ply.more.at("reason")[i], reason[f]) << i;
    ++i;
  }
}

std::string header(int vertices, int faces, const std::string& face_properties = "property float view\n") {
  return "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex " + std::to_string(vertices) +
         "\nproperty double x\nproperty double y\nproperty double z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\n" + face_properties + "end_header\n";
}

TEST(PlyFaceValues, AHandWrittenTriangleReadsAsWritten) {
  TempFile tmp(".ply");
  tmp.write(header(3, 1) + "0 0 0\n1 0 0\n0 1.5 -2\n3 0 1 2 0.25\n");
  const PlyFaceValues ply = read_ply_with_face_values(tmp.path());
  ASSERT_EQ(ply.positions.size(), 3u);
  EXPECT_EQ(ply.positions[2], Vec3(0, 1.5, -2));
  ASSERT_EQ(ply.faces.size(), 1u);
  EXPECT_EQ(ply.faces[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(ply.values[0], 0.25);
}

TEST(PlyFaceValues, MalformedFilesAreRefusedAtTheirLine) {
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n";
  const struct {
    std::string text, place, problem;
  } cases[] = {
      {"solid x\n", "line 1", "not a PLY file"},
      {"ply\nformat binary_little_endian 1.0\n", "line 2", "only 'format ascii 1.0'"},
      {header(3, 1) + body + "3 0 1 7 0.5\n", "line 15", "bad vertex index '7' (0 to 2)"},
      {header(3, 1) + body + "4 0 1 2 0.5\n", "line 15", "a face needs '3'"},
      {header(3, 1) + body + "3 0 1 2 0.5 1\n", "line 15", "its 1 value(s)"},
      {header(3, 1, "property float view\nproperty float view\n") + body, "line 11", "the face property 'view' twice"},
      {header(3, 1, "") + body, "line 10", "expected a scalar face property after vertex_indices"},
      {header(3, 1) + body + "3 0 1 2 nan\n", "line 15", "expected a number, found 'nan'"},
      {header(3, 1) + "0 0 0\n1 0 x\n", "line 13", "expected a number, found 'x'"},
      {header(3, 1) + "0 0 0\n1 0 1e9\n", "line 13", "beyond 100 km"},
      {header(3, 2) + body + "3 0 1 2 0.5\n", "line 15", "the file ends early"},
      {header(3, 1) + body + "3 0 1 2 0.5\n3 0 1 2 0.5\n", "line 16", "more than the header's 3 vertices and 1 faces"},
      {header(-1, 1), "line 4", "bad vertex count '-1'"},
      {header(1 << 28, 1) + body, "line 14", "the file ends early"},  // nothing allocated for what the header claims
  };
  for (const auto& c : cases) {
    TempFile tmp(".ply");
    tmp.write(c.text);
    try {
      read_ply_with_face_values(tmp.path());
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(contains(message, tmp.path())) << message;
      EXPECT_TRUE(contains(message, c.place)) << message << " / " << c.place;
      EXPECT_TRUE(contains(message, c.problem)) << message << " / " << c.problem;
    }
  }
}

}  // namespace
}  // namespace vdc
