// Tests of OBJ import/export (src/io/obj.*): exact round trip, error reporting, polygons, indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/mesh.hpp"
#include "core/mesh_build.hpp"
#include "io/obj.hpp"
#include "support/temp_file.hpp"
#include "support/text.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

std::string data_path(const std::string& name) { return std::string(VDCLOTH_TEST_DATA) + "/" + name; }

using test::contains;

using test::TempFile;

bool same_bits(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }

std::set<std::pair<int, int>> seam_edges(const Mesh& m) {
  std::set<std::pair<int, int>> s;
  for (EdgeId e : m.edges())
    if (m.is_seam(e)) {
      int a = m.edge_node(e, 0).idx, b = m.edge_node(e, 1).idx;
      s.insert({std::min(a, b), std::max(a, b)});
    }
  return s;
}

std::set<std::pair<int, int>> boundary_edges(const Mesh& m) {
  std::set<std::pair<int, int>> s;
  for (EdgeId e : m.edges())
    if (m.is_boundary(e)) {
      int a = m.edge_node(e, 0).idx, b = m.edge_node(e, 1).idx;
      s.insert({std::min(a, b), std::max(a, b)});
    }
  return s;
}

// Exact comparison of two compact meshes, index by index.
void expect_identical(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.num_verts(), b.num_verts());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  ASSERT_EQ(a.num_edges(), b.num_edges());
  for (NodeId n : a.nodes())
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(same_bits(a.x(n)[k], b.x(n)[k])) << "node " << n.idx << " coord " << k << ": " << a.x(n)[k]
                                                   << " vs " << b.x(n)[k];
  for (VertId v : a.verts()) {
    for (int k = 0; k < 2; ++k)
      EXPECT_TRUE(same_bits(a.u(v)[k], b.u(v)[k])) << "vert " << v.idx << " coord " << k << ": " << a.u(v)[k]
                                                   << " vs " << b.u(v)[k];
    EXPECT_EQ(a.vert_node(v), b.vert_node(v)) << "vert " << v.idx;
  }
  for (FaceId f : a.faces()) EXPECT_EQ(a.face_verts(f), b.face_verts(f)) << "face " << f.idx;
  EXPECT_EQ(seam_edges(a), seam_edges(b));
  EXPECT_EQ(boundary_edges(a), boundary_edges(b));
}

// A 2 x 1 grid of cells whose middle column of nodes carries two uvs: the left cell is one pattern
// piece, the right cell another, 0.5 m to its right in material space. Coordinates are chosen to
// need all 17 significant digits (and include -0.0).
MeshSource two_piece_grid() {
  MeshSource s;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 2; ++i) s.positions.emplace_back(i / 3.0, 0.1 * i * j + 1e-3 * j, -(j / 7.0));
  // Left piece: nodes 0, 1, 3, 4 -> uvs 0..3. Right piece: nodes 1, 2, 4, 5 -> uvs 4..7.
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) s.uvs.emplace_back(i / 3.0, j / 7.0);
  for (int j = 0; j <= 1; ++j)
    for (int i = 1; i <= 2; ++i) s.uvs.emplace_back(i / 3.0 + 0.5, j / 7.0);
  auto L = [](int node, int uv) { return Corner{node, uv}; };
  s.faces = {{L(0, 0), L(1, 1), L(4, 3)}, {L(0, 0), L(4, 3), L(3, 2)},   // left cell
             {L(1, 4), L(2, 5), L(4, 6)}, {L(2, 5), L(5, 7), L(4, 6)}};  // right cell
  return s;
}

// ----------------------------------------------------------------------------------------------
// Round trip

TEST(ObjRoundTrip, SeamedMeshComesBackExactly) {
  Mesh m = build_mesh(two_piece_grid());
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  ASSERT_EQ(m.num_nodes(), 6);
  ASSERT_EQ(m.num_verts(), 8);
  ASSERT_EQ(m.num_faces(), 4);
  ASSERT_EQ(seam_edges(m), (std::set<std::pair<int, int>>{{1, 4}}));
  ASSERT_TRUE(std::signbit(m.x(NodeId(0)).z()));  // -0.0 survives construction

  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path()));
  Mesh back = read_obj(tmp.path());
  EXPECT_TRUE(back.validate().ok()) << back.validate().summary();
  expect_identical(m, back);
  EXPECT_EQ(seam_edges(back), (std::set<std::pair<int, int>>{{1, 4}}));
  EXPECT_EQ(back.node_verts(NodeId(1)).size(), 2u);
  EXPECT_EQ(back.node_verts(NodeId(4)).size(), 2u);

  // Writing the read-back mesh gives the same file, byte for byte.
  TempFile tmp2;
  ASSERT_TRUE(write_obj(back, tmp2.path()));
  std::ifstream f1(tmp.path(), std::ios::binary), f2(tmp2.path(), std::ios::binary);
  std::string s1((std::istreambuf_iterator<char>(f1)), std::istreambuf_iterator<char>());
  std::string s2((std::istreambuf_iterator<char>(f2)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(s1.empty());
  EXPECT_EQ(s1, s2);
}

TEST(ObjRoundTrip, GridComesBackExactly) {
  Mesh m = build_mesh(make_grid(0.7, 1.3, 5, 4));
  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path()));
  Mesh back = read_obj(tmp.path());
  expect_identical(m, back);
  EXPECT_TRUE(seam_edges(back).empty());
}

// After edits and compaction, vert order need not be the order of first use; the read-back mesh
// must still describe the same faces: same corners (world and material position), same order.
TEST(ObjRoundTrip, EditedMeshComesBackWithSameFaces) {
  Mesh m = build_mesh(make_grid(1, 1, 3, 3));
  m.remove_face(FaceId(0));
  // Face 8 is (5, 6, 10): all three corners are interior, so the hole keeps every vertex manifold
  // (removing a face at a boundary node in the middle of its fan would make a bow tie, which
  // validate() does not check but read_obj refuses).
  m.remove_face(FaceId(8));
  // Face 0 comes back with a new vert on node 0 (same uv, so a zero-width seam along 0-5): the
  // verts are no longer numbered in order of first use.
  // Grid faces 0 and 1 are (as nodes) (0, 1, 5) and (0, 5, 4).
  const VertId v0 = m.node_verts(NodeId(0)).at(0), v1 = m.node_verts(NodeId(1)).at(0), v5 = m.node_verts(NodeId(5)).at(0);
  VertId nv = m.add_vert(NodeId(0), m.u(v0));
  m.add_face(nv, v1, v5);
  m.compact();
  for (VertId v : m.verts())
    if (m.vert_faces(v).empty()) m.remove_vert(v);
  m.compact();
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();

  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path()));
  Mesh back = read_obj(tmp.path());
  ASSERT_TRUE(back.validate().ok()) << back.validate().summary();
  ASSERT_EQ(back.num_nodes(), m.num_nodes());
  ASSERT_EQ(back.num_verts(), m.num_verts());
  ASSERT_EQ(back.num_edges(), m.num_edges());
  ASSERT_EQ(back.num_faces(), m.num_faces());
  for (NodeId n : m.nodes()) EXPECT_EQ(back.x(n), m.x(n)) << "node " << n.idx;
  for (FaceId f : m.faces())
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(back.face_node(f, k), m.face_node(f, k)) << "face " << f.idx << " corner " << k;
      EXPECT_EQ(back.u(back.face_vert(f, k)), m.u(m.face_vert(f, k))) << "face " << f.idx << " corner " << k;
    }
  EXPECT_EQ(seam_edges(back), seam_edges(m));
}

// Rounded to the micrometre (as a run writes its frames): every coordinate within half a
// micrometre of the mesh's, the same faces and seams; 1/3 m is written as 0.333333.
TEST(ObjRoundTrip, RoundedToDecimalsComesBackWithinHalfAUnit) {
  Mesh m = build_mesh(two_piece_grid());
  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path(), ObjWriting{true, 6}));
  std::ifstream in(tmp.path());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(text, "\nv 0.333333 0 0\n")) << text;
  Mesh back = read_obj(tmp.path());
  ASSERT_EQ(back.num_nodes(), m.num_nodes());
  ASSERT_EQ(back.num_verts(), m.num_verts());
  for (NodeId n : m.nodes()) EXPECT_LE((back.x(n) - m.x(n)).cwiseAbs().maxCoeff(), 0.5e-6 + 1e-15) << n.idx;
  for (VertId v : m.verts()) EXPECT_LE((back.u(v) - m.u(v)).cwiseAbs().maxCoeff(), 0.5e-6 + 1e-15) << v.idx;
  for (FaceId f : m.faces()) EXPECT_EQ(back.face_verts(f), m.face_verts(f)) << f.idx;
  EXPECT_EQ(seam_edges(back), seam_edges(m));
}

// Without material coordinates (obstacles): no vt, faces as "f a b c", read back as an obstacle
// with the same positions and faces.
TEST(ObjRoundTrip, WithoutMaterialHasNoTextureCoordinates) {
  Mesh m = build_mesh(make_grid(0.7, 1.3, 5, 4));
  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path(), ObjWriting{false, -1}));
  std::ifstream in(tmp.path());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(contains(text, "vt ")) << text;
  EXPECT_FALSE(contains(text, "/")) << text;
  EXPECT_TRUE(contains(text, "\nf 1 2 8\n")) << text;
  const MeshSource back = read_obj_source(tmp.path(), false);
  const MeshSource src = mesh_source(m);
  ASSERT_EQ(back.positions.size(), src.positions.size());
  for (std::size_t i = 0; i < src.positions.size(); ++i) EXPECT_EQ(back.positions[i], src.positions[i]) << i;
  ASSERT_EQ(back.faces.size(), src.faces.size());
  for (std::size_t i = 0; i < src.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(back.faces[i][k].node, src.faces[i][k].node) << i;
}

// Two square pieces whose material squares overlap ([0, 1]^2 and [0.5, 1.5]^2, as a dress's
// bodice lies within its skirt's box): separated in a row, the first kept where it is, the
// second moved to start 2 cm after it with its lowest v at 0, i.e. by (1.02 - 0.5, -0.5).
MeshSource two_overlapping_pieces() {
  MeshSource s;
  for (int piece = 0; piece < 2; ++piece) {
    const double at = 0.5 * piece;
    for (int k = 0; k < 4; ++k) {
      const Vec2 corner(k == 1 || k == 2 ? 1 : 0, k >= 2 ? 1 : 0);
      s.positions.emplace_back(corner.x() + 3 * piece, corner.y(), 0);
      s.uvs.push_back(corner + Vec2(at, at));
    }
    const int32_t b = 4 * piece;
    s.faces.push_back({Corner{b, b}, Corner{b + 1, b + 1}, Corner{b + 2, b + 2}});
    s.faces.push_back({Corner{b, b}, Corner{b + 2, b + 2}, Corner{b + 3, b + 3}});
  }
  return s;
}

TEST(ObjRoundTrip, OverlappingPiecesAreWrittenSideBySideWithTheirShapes) {
  const MeshSource source = two_overlapping_pieces();
  const std::vector<Vec2> offsets = piece_offsets(source);
  ASSERT_EQ(offsets.size(), 8u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(offsets[static_cast<std::size_t>(i)], Vec2(0, 0)) << i;
  for (int i = 4; i < 8; ++i) EXPECT_LT((offsets[static_cast<std::size_t>(i)] - Vec2(0.52, -0.5)).norm(), 1e-12) << i;
  MeshSource apart = source;
  for (int i = 4; i < 8; ++i) apart.uvs[static_cast<std::size_t>(i)] += Vec2(2, 0);
  for (const Vec2& o : piece_offsets(apart)) EXPECT_EQ(o, Vec2(0, 0)) << "pieces apart stay where they are";

  Mesh m = build_mesh(source);
  TempFile tmp;
  ASSERT_TRUE(write_obj(m, tmp.path(), ObjWriting{true, -1, true}));
  Mesh back = read_obj(tmp.path());
  ASSERT_EQ(back.num_verts(), m.num_verts());
  for (FaceId f : m.faces()) EXPECT_NEAR(back.material_area(f), m.material_area(f), 1e-12) << f.idx;
  for (VertId v : m.verts()) EXPECT_EQ(back.x(m.vert_node(v)), m.x(m.vert_node(v)));
  ASSERT_TRUE(write_obj(m, tmp.path(), ObjWriting{true, -1, false}));
  back = read_obj(tmp.path());
  for (VertId v : m.verts()) EXPECT_EQ(back.u(v), m.u(v)) << "without separate_pieces, vt is material space as it is";
}

TEST(ObjRoundTrip, WriteToUnwritablePathFails) {
  Mesh m = build_mesh(make_grid(1, 1, 1, 1));
  TempFile dir_that_is_missing("");
  EXPECT_FALSE(write_obj(m, dir_that_is_missing.path() + "/sub/mesh.obj"));
}

// ----------------------------------------------------------------------------------------------
// Errors: InputError naming the file, the line and the problem.

struct ObjErrorCase {
  const char* file;
  int line;  // 0: no line
  std::vector<std::string> words;
};

InputError read_error(const std::string& path, bool require_uv = true) {
  try {
    read_obj(path, require_uv);
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": threw something other than InputError: " << e.what();
    return InputError("", "", "wrong exception");
  }
  ADD_FAILURE() << path << ": read_obj accepted a bad file";
  return InputError("", "", "no exception");
}

void expect_error(const ObjErrorCase& c) {
  SCOPED_TRACE(c.file);
  std::string path = data_path(c.file);
  ASSERT_TRUE(fs::exists(path)) << path;
  InputError e = read_error(path);
  std::string what = e.what();
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(contains(what, path)) << what;
  if (c.line > 0) {
    EXPECT_EQ(e.place(), "line " + std::to_string(c.line)) << what;
    EXPECT_TRUE(contains(what, path + ":line " + std::to_string(c.line) + ": ")) << what;
  }
  for (const auto& w : c.words) EXPECT_TRUE(contains(what, w)) << "missing '" << w << "' in: " << what;
}

TEST(ObjErrors, NonManifoldEdge) { expect_error({"nonmanifold.obj", 19, {"non-manifold"}}); }

TEST(ObjErrors, InconsistentOrientation) { expect_error({"flipped.obj", 14, {"inconsistently oriented"}}); }

TEST(ObjErrors, ZeroAreaInMaterialSpace) { expect_error({"zero_area.obj", 11, {"zero area", "material space"}}); }

TEST(ObjErrors, ZeroAreaInWorldSpace) { expect_error({"zero_area_world.obj", 15, {"zero area", "world space"}}); }

TEST(ObjErrors, ClockwiseInMaterialSpace) { expect_error({"clockwise.obj", 11, {"clockwise", "material space"}}); }

TEST(ObjErrors, CoordinateBeyondAHundredKilometres) { expect_error({"far_vertex.obj", 4, {"1e308", "beyond 100 km"}}); }

TEST(ObjErrors, BadNumber) { expect_error({"bad_number.obj", 4, {"expected a number", "1x"}}); }

TEST(ObjErrors, MissingTextureIndex) { expect_error({"missing_vt.obj", 11, {"vt"}}); }

TEST(ObjErrors, IndexOutOfRange) { expect_error({"index_out_of_range.obj", 8, {"out of range", "4"}}); }

TEST(ObjErrors, BowTieVertex) {
  std::string path = data_path("bowtie.obj");
  InputError e = read_error(path);
  EXPECT_TRUE(e.place() == "line 12" || e.place() == "line 13") << e.what();
  EXPECT_TRUE(contains(e.what(), path)) << e.what();
  EXPECT_TRUE(contains(e.what(), "non-manifold")) << e.what();
}

TEST(ObjErrors, MissingFile) {
  TempFile never_written;
  InputError e = read_error(never_written.path());
  EXPECT_TRUE(contains(e.what(), "file not found")) << e.what();
  EXPECT_TRUE(contains(e.what(), never_written.path())) << e.what();
}

TEST(ObjErrors, MissingVtIsFineForObstacles) {
  // Without require_uv (obstacles), vt is ignored: corner k of every face takes the k-th corner
  // of one canonical counter-clockwise material triangle.
  Mesh m = read_obj(data_path("missing_vt.obj"), false);
  EXPECT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.num_faces(), 2);
  const std::array<Vec2, 3> canonical{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  for (FaceId f : m.faces())
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.u(m.face_vert(f, k)), canonical[static_cast<std::size_t>(k)]);
}

TEST(ObjErrors, IcosphereIsAClosedOutwardMesh) {
  Mesh m = build_mesh(make_icosphere(0.1, 2));
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_faces(), 20 * 16);
  EXPECT_EQ(m.num_nodes() - m.num_edges() + m.num_faces(), 2);  // Euler characteristic of a sphere
  for (EdgeId e : m.edges()) EXPECT_FALSE(m.is_boundary(e));
  for (FaceId f : m.faces()) {
    Vec3 centre = (m.x(m.face_node(f, 0)) + m.x(m.face_node(f, 1)) + m.x(m.face_node(f, 2))) / 3;
    EXPECT_GT(m.world_normal(f).dot(centre), 0);  // outward
  }
}

TEST(ObjErrors, MoreBadInputs) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 0 1\n";
  struct Case {
    std::string text;
    int line;
    std::string word;
  };
  const std::vector<Case> cases = {
      {head + "f 1/1 2/2 3/4\n", 7, "texture index 4 out of range"},
      {head + "f 0/1 2/2 3/3\n", 7, "bad position index '0'"},
      {head + "f 1/1 2/2\n", 7, "at least 3 corners"},
      {head + "f 1/1 2/x 3/3\n", 7, "bad texture index 'x'"},
      {"v 0 0\n" + head, 1, "'v' needs 3 coordinates"},
      {head + "vt 0\nf 1/1 2/2 3/3\n", 7, "'vt' needs 2 coordinates"},
      {head + "v 1 nan 0\nf 1/1 2/2 3/3\n", 7, "expected a number"},
      {head + "vt inf 0\nf 1/1 2/2 3/3\n", 7, "expected a number"},
      {"# comment only\n" + head, 0, "no faces"},
      {head + "f 1/1 2/2 3/3\nf 1/1 2/2 3/3 \n", 8, "inconsistently oriented"},  // the same face twice
      // Indices refer to what is defined so far, not to the whole file.
      {head + "f 1/1 2/2 4/3\nv 1 0 -1\n", 7, "out of range"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    TempFile tmp;
    tmp.write(c.text);
    InputError e = read_error(tmp.path());
    EXPECT_EQ(e.file(), tmp.path());
    if (c.line > 0)
      EXPECT_EQ(e.place(), "line " + std::to_string(c.line)) << e.what();
    else
      EXPECT_EQ(e.place(), "") << e.what();
    EXPECT_TRUE(contains(e.what(), c.word)) << "missing '" << c.word << "' in: " << e.what();
  }
}

// ----------------------------------------------------------------------------------------------
// Polygons, indices and ignored statements

TEST(ObjRead, QuadIsSplitIntoTwoTriangles) {
  Mesh m = read_obj(data_path("quad.obj"));
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.num_verts(), 4);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_edges(), 5);
  // A fan from the first corner: (1, 2, 3) and (1, 3, 4).
  EXPECT_EQ(m.face_node(FaceId(0), 0).idx, 0);
  EXPECT_EQ(m.face_node(FaceId(0), 1).idx, 1);
  EXPECT_EQ(m.face_node(FaceId(0), 2).idx, 2);
  EXPECT_EQ(m.face_node(FaceId(1), 0).idx, 0);
  EXPECT_EQ(m.face_node(FaceId(1), 1).idx, 2);
  EXPECT_EQ(m.face_node(FaceId(1), 2).idx, 3);
  double area = 0;
  for (FaceId f : m.faces()) area += m.material_area(f);
  EXPECT_DOUBLE_EQ(area, 1.0);
  EdgeId diag = m.find_edge(NodeId(0), NodeId(2));
  ASSERT_TRUE(diag.valid());
  EXPECT_FALSE(m.is_boundary(diag));
  EXPECT_FALSE(m.is_seam(diag));
  EXPECT_EQ(m.x(NodeId(2)), Vec3(1, 0, -1));
  EXPECT_EQ(m.u(m.face_vert(FaceId(1), 2)), Vec2(0, 1));
}

TEST(ObjRead, PolygonLinesMapErrorsToTheirLine) {
  // A pentagon makes three triangles from one line; an error in a later face still names its line.
  TempFile tmp;
  tmp.write(
      "v 0 0 0\nv 1 0 0\nv 2 0 -1\nv 1 0 -2\nv 0 0 -1\nv 5 0 5\n"
      "vt 0 0\nvt 1 0\nvt 2 1\nvt 1 2\nvt 0 1\n"
      "f 1/1 2/2 3/3 4/4 5/5\n"  // line 12
      "f 1/1 2/2 6/3\n");        // line 13: runs 1 -> 2 again
  std::vector<int> lines;
  MeshSource src = read_obj_source(tmp.path(), true, &lines);
  ASSERT_EQ(src.faces.size(), 4u);
  EXPECT_EQ(lines, (std::vector<int>{12, 12, 12, 13}));
  InputError e = read_error(tmp.path());
  EXPECT_EQ(e.place(), "line 13") << e.what();
}

TEST(ObjRead, NegativeIndicesAreRelative) {
  Mesh m = read_obj(data_path("negative_indices.obj"));
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.num_verts(), 4);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_edges(), 5);
  // Face 0 is (1, 2, 3); face 1 is (1, 3, 4), with -2 and -1 counted from the 4 positions read
  // by then (not from the 3 of the first face).
  const std::array<std::array<Vec3, 3>, 2> x = {{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, -1)},
                                                 {Vec3(0, 0, 0), Vec3(1, 0, -1), Vec3(0, 0, -1)}}};
  const std::array<std::array<Vec2, 3>, 2> u = {{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)},
                                                 {Vec2(0, 0), Vec2(1, 1), Vec2(0, 1)}}};
  for (int f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(m.x(m.face_node(FaceId(f), k)), x[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)])
          << "face " << f << " corner " << k;
      EXPECT_EQ(m.u(m.face_vert(FaceId(f), k)), u[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)])
          << "face " << f << " corner " << k;
    }
  // Both faces share the verts of positions 1 and 3.
  EXPECT_EQ(m.face_vert(FaceId(0), 0), m.face_vert(FaceId(1), 0));
  EXPECT_EQ(m.face_vert(FaceId(0), 2), m.face_vert(FaceId(1), 1));
}

TEST(ObjRead, IgnoresNormalsGroupsCommentsAndCrlf) {
  TempFile tmp;
  tmp.write(
      "# exported by something\r\n"
      "mtllib cloth.mtl\r\n"
      "o Cloth\r\n"
      "v 0 0 0 # trailing comment\r\n"
      "v 1.5e0 0 0\r\n"
      "v 0 0 -1.0\r\n"
      "vt 0 0\r\n"
      "vt 1.5 0 0\r\n"  // a third vt coordinate is ignored
      "vt 0 1\r\n"
      "vn 0 1 0\r\n"
      "g panel\r\n"
      "usemtl fabric\r\n"
      "s off\r\n"
      "\r\n"
      "f 1/1/1 2/2/1 3/3/1\r\n");
  Mesh m = read_obj(tmp.path());
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_nodes(), 3);
  EXPECT_EQ(m.num_faces(), 1);
  EXPECT_EQ(m.x(NodeId(1)), Vec3(1.5, 0, 0));
  EXPECT_EQ(m.x(NodeId(2)), Vec3(0, 0, -1));
  EXPECT_EQ(m.u(VertId(1)), Vec2(1.5, 0));
  EXPECT_DOUBLE_EQ(m.material_area(FaceId(0)), 0.75);
}

TEST(ObjRead, VertexNormalOnlyCornersNeedVt) {
  // f v//vn has no texture index: a garment must refuse it.
  TempFile tmp;
  tmp.write("v 0 0 0\nv 1 0 0\nv 0 0 -1\nvn 0 1 0\nf 1//1 2//1 3//1\n");
  InputError e = read_error(tmp.path());
  EXPECT_EQ(e.place(), "line 5") << e.what();
  EXPECT_TRUE(contains(e.what(), "vt")) << e.what();
  Mesh m = read_obj(tmp.path(), false);
  EXPECT_EQ(m.num_faces(), 1);
  EXPECT_TRUE(m.validate().ok());
}

TEST(ObjRead, SeamFromSharedPositionWithTwoVt) {
  // Two triangles share positions 2 and 3 but each side has its own vt: one seam edge.
  TempFile tmp;
  tmp.write(
      "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 2.5 0\nvt 2.5 1\nvt 1.5 1\n"
      "f 1/1 2/2 3/3\nf 2/4 4/5 3/6\n");
  Mesh m = read_obj(tmp.path());
  ASSERT_TRUE(m.validate().ok()) << m.validate().summary();
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.num_verts(), 6);
  EXPECT_EQ(seam_edges(m), (std::set<std::pair<int, int>>{{1, 2}}));
}

}  // namespace
}  // namespace vdc
