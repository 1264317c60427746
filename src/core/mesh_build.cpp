#include "core/mesh_build.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <string>

namespace vdc {

namespace {

// Positions as the file numbers them (1-based).
std::string corner_list(const std::array<Corner, 3>& f) {
  return std::to_string(f[0].node + 1) + ", " + std::to_string(f[1].node + 1) + ", " + std::to_string(f[2].node + 1);
}

// Why add_face refused a face, in the file's terms: which edge, by 1-based position numbers.
std::string refusal(const Mesh& mesh, const std::vector<NodeId>& node_of, const std::array<Corner, 3>& f) {
  for (int i = 0; i < 3; ++i) {
    const Corner &p = f[static_cast<std::size_t>(i)], &q = f[static_cast<std::size_t>((i + 1) % 3)];
    NodeId a = node_of[static_cast<std::size_t>(p.node)], b = node_of[static_cast<std::size_t>(q.node)];
    EdgeId e = mesh.find_edge(a, b);
    if (!e.valid()) continue;
    const std::string edge = "edge between positions " + std::to_string(p.node + 1) + " and " + std::to_string(q.node + 1);
    if (mesh.edge_face(e, 0).valid() && mesh.edge_face(e, 1).valid()) return "non-manifold " + edge + " (a third face)";
    int side = mesh.edge_node(e, 0) == a ? 0 : 1;
    if (mesh.edge_face(e, side).valid()) return "inconsistently oriented faces at the " + edge;
  }
  return "face refused";
}

// Relative area below which a triangle counts as degenerate: area < kDegenerate * (longest edge)^2.
constexpr double kDegenerate = 1e-10;

template <class V>
bool degenerate(double area, const V& a, const V& b, const V& c) {
  double l2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !(std::abs(area) > kDegenerate * l2) || l2 == 0;
}

}  // namespace

Mesh build_mesh(const MeshSource& src) {
  const auto np = static_cast<int32_t>(src.positions.size());
  const auto nu = static_cast<int32_t>(src.uvs.size());
  std::vector<char> used(src.positions.size(), 0);
  for (std::size_t fi = 0; fi < src.faces.size(); ++fi) {
    for (const Corner& c : src.faces[fi]) {
      if (c.node < 0 || c.node >= np)
        throw MeshBuildError(static_cast<int32_t>(fi), "position index " + std::to_string(c.node + 1) + " out of range");
      if (c.uv < 0 || c.uv >= nu)
        throw MeshBuildError(static_cast<int32_t>(fi), "texture (material) index " + std::to_string(c.uv + 1) + " out of range");
      used[static_cast<std::size_t>(c.node)] = 1;
    }
  }
  Mesh mesh;
  std::vector<NodeId> node_of(src.positions.size());
  std::vector<int32_t> first_face_of_node, source_of;
  for (std::size_t i = 0; i < src.positions.size(); ++i) {
    if (!used[i]) continue;
    if (!src.positions[i].allFinite()) throw MeshBuildError(-1, "position " + std::to_string(i + 1) + " is not finite");
    node_of[i] = mesh.add_node(src.positions[i]);
    first_face_of_node.push_back(-1);
    source_of.push_back(static_cast<int32_t>(i));
  }
  // The vert of each (position, pattern position) pair of the source, made at its first corner.
  std::unordered_map<uint64_t, VertId> vert_of;
  vert_of.reserve(src.uvs.size());
  for (std::size_t fi = 0; fi < src.faces.size(); ++fi) {
    const auto& f = src.faces[fi];
    const auto face_index = static_cast<int32_t>(fi);
    if (f[0].node == f[1].node || f[1].node == f[2].node || f[0].node == f[2].node)
      throw MeshBuildError(face_index, "degenerate face: it repeats a position (" + corner_list(f) + ")");
    const Vec3 &x0 = src.positions[static_cast<std::size_t>(f[0].node)], &x1 = src.positions[static_cast<std::size_t>(f[1].node)],
               &x2 = src.positions[static_cast<std::size_t>(f[2].node)];
    const Vec2 &u0 = src.uvs[static_cast<std::size_t>(f[0].uv)], &u1 = src.uvs[static_cast<std::size_t>(f[1].uv)],
               &u2 = src.uvs[static_cast<std::size_t>(f[2].uv)];
    if (!u0.allFinite() || !u1.allFinite() || !u2.allFinite())
      throw MeshBuildError(face_index, "material-space coordinate is not finite");
    double ua = 0.5 * signed_area2(u0, u1, u2);
    if (degenerate(ua, u0, u1, u2)) throw MeshBuildError(face_index, "degenerate face: zero area in material space (vt)");
    if (ua < 0)
      throw MeshBuildError(face_index, "face is clockwise in material space (vt); faces must be counter-clockwise");
    double xa = 0.5 * area_normal(x0, x1, x2).norm();
    if (degenerate(xa, x0, x1, x2)) throw MeshBuildError(face_index, "degenerate face: zero area in world space (v)");
    std::array<VertId, 3> vs;
    for (int k = 0; k < 3; ++k) {
      const Corner& c = f[static_cast<std::size_t>(k)];
      const uint64_t key = (static_cast<uint64_t>(static_cast<uint32_t>(c.node)) << 32) | static_cast<uint32_t>(c.uv);
      auto it = vert_of.find(key);
      if (it == vert_of.end()) it = vert_of.emplace(key, mesh.add_vert(node_of[static_cast<std::size_t>(c.node)], src.uvs[static_cast<std::size_t>(c.uv)])).first;
      vs[static_cast<std::size_t>(k)] = it->second;
      auto& first = first_face_of_node[static_cast<std::size_t>(node_of[static_cast<std::size_t>(c.node)].idx)];
      if (first < 0) first = face_index;
    }
    try {
      mesh.add_face(vs[0], vs[1], vs[2]);
    } catch (const TopologyError&) {
      throw MeshBuildError(face_index, refusal(mesh, node_of, f));
    }
  }
  for (NodeId n : mesh.nodes())
    if (int fans = mesh.fan_count(n); fans > 1)
      throw MeshBuildError(first_face_of_node[static_cast<std::size_t>(n.idx)],
                           "non-manifold vertex: the faces around position " + std::to_string(source_of[static_cast<std::size_t>(n.idx)] + 1) +
                               " form " + std::to_string(fans) + " separate fans");
  return mesh;
}

MeshSource mesh_source(const Mesh& mesh) {
  MeshSource src;
  std::vector<int32_t> node_index(static_cast<std::size_t>(mesh.node_capacity()), -1);
  std::vector<int32_t> vert_index(static_cast<std::size_t>(mesh.vert_capacity()), -1);
  for (NodeId n : mesh.nodes()) {
    node_index[static_cast<std::size_t>(n.idx)] = static_cast<int32_t>(src.positions.size());
    src.positions.push_back(mesh.x(n));
  }
  for (VertId v : mesh.verts()) {
    vert_index[static_cast<std::size_t>(v.idx)] = static_cast<int32_t>(src.uvs.size());
    src.uvs.push_back(mesh.u(v));
  }
  for (FaceId f : mesh.faces()) {
    std::array<Corner, 3> c;
    for (int k = 0; k < 3; ++k) {
      VertId v = mesh.face_vert(f, k);
      c[static_cast<std::size_t>(k)] = {node_index[static_cast<std::size_t>(mesh.vert_node(v).idx)], vert_index[static_cast<std::size_t>(v.idx)]};
    }
    src.faces.push_back(c);
  }
  return src;
}

std::vector<std::array<int32_t, 3>> position_triangles(const MeshSource& source) {
  std::vector<std::array<int32_t, 3>> faces;
  faces.reserve(source.faces.size());
  for (const auto& f : source.faces) faces.push_back({f[0].node, f[1].node, f[2].node});
  return faces;
}

MeshSource make_grid(double size_x, double size_y, int nx, int ny) {
  MeshSource src;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Vec2 u(size_x * i / nx, size_y * j / ny);
      src.uvs.push_back(u);
      src.positions.emplace_back(u.x(), 0.0, -u.y());
    }
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  auto corner = [](int32_t k) { return Corner{k, k}; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        src.faces.push_back({corner(a), corner(b), corner(c)});
        src.faces.push_back({corner(a), corner(c), corner(d)});
      } else {
        src.faces.push_back({corner(a), corner(b), corner(d)});
        src.faces.push_back({corner(b), corner(c), corner(d)});
      }
    }
  return src;
}

void with_canonical_uvs(MeshSource& src) {
  src.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  for (auto& f : src.faces)
    for (int k = 0; k < 3; ++k) f[static_cast<std::size_t>(k)].uv = k;
}

MeshSource make_icosphere(double radius, int subdivisions) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int32_t, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                           {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                           {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& v : p) v.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto midpoint = [&](int32_t a, int32_t b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back((p[static_cast<std::size_t>(a)] + p[static_cast<std::size_t>(b)]).normalized());
      return mid[key] = static_cast<int32_t>(p.size() - 1);
    };
    std::vector<std::array<int32_t, 3>> next;
    for (const auto& t : f) {
      int32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  MeshSource src;
  for (const auto& v : p) src.positions.push_back(radius * v);
  for (const auto& t : f) src.faces.push_back({Corner{t[0], 0}, Corner{t[1], 0}, Corner{t[2], 0}});
  with_canonical_uvs(src);
  return src;
}

double enclosed_volume(const MeshSource& mesh, const std::vector<Vec3>& x) {
  double v = 0;
  for (const auto& f : mesh.faces)
    v += x[static_cast<std::size_t>(f[0].node)].dot(x[static_cast<std::size_t>(f[1].node)].cross(x[static_cast<std::size_t>(f[2].node)]));
  return v / 6;
}

}  // namespace vdc
