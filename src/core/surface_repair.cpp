// Surface repair for obstacles (surface_repair.hpp): orientation by a breadth-first walk over
// edges shared by exactly two faces, fans of faces around each vertex by union-find over those
// edges.
#include "core/surface_repair.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <numeric>
#include <set>

namespace vdc {

namespace {

// Disjoint sets of integers.
class Partition {
 public:
  explicit Partition(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int a) {
    while (parent_[static_cast<std::size_t>(a)] != a) a = parent_[static_cast<std::size_t>(a)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(a)])];
    return a;
  }
  void join(int a, int b) { parent_[static_cast<std::size_t>(find(a))] = find(b); }

 private:
  std::vector<int> parent_;
};

using Tri = std::array<int32_t, 3>;

// The undirected edges of triangles, each with its faces and the corner each starts at.
struct EdgeUse {
  int face;
  int corner;  // the edge runs from corner to corner + 1 of the face
};
std::map<std::pair<int32_t, int32_t>, std::vector<EdgeUse>> edges_of(const std::vector<Tri>& tris) {
  std::map<std::pair<int32_t, int32_t>, std::vector<EdgeUse>> edges;
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tris[f][static_cast<std::size_t>(k)], b = tris[f][static_cast<std::size_t>((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back({static_cast<int>(f), k});
    }
  return edges;
}

// Whether the face's edge at `corner` runs from the smaller position to the larger.
bool runs_up(const Tri& t, int corner) { return t[static_cast<std::size_t>(corner)] < t[static_cast<std::size_t>((corner + 1) % 3)]; }

// Faces kept: a face with no area (relative to its longest edge, as build_mesh judges), a
// repeated corner, or the corners of a face kept before, is dropped.
std::vector<int> kept_faces(const MeshSource& s, int& dropped) {
  std::set<Tri> seen;
  std::vector<int> kept;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const auto& c = s.faces[f];
    Tri key{c[0].node, c[1].node, c[2].node};
    const Vec3 &a = s.positions[static_cast<std::size_t>(key[0])], &b = s.positions[static_cast<std::size_t>(key[1])], &d = s.positions[static_cast<std::size_t>(key[2])];
    const double l2 = std::max({(b - a).squaredNorm(), (d - b).squaredNorm(), (a - d).squaredNorm()});
    std::sort(key.begin(), key.end());
    const bool flat = !(0.5 * (b - a).cross(d - a).norm() > 1e-9 * l2) || l2 == 0;
    if (flat || key[0] == key[1] || key[1] == key[2] || !seen.insert(key).second) {
      ++dropped;
      continue;
    }
    kept.push_back(static_cast<int>(f));
  }
  return kept;
}

// Turns faces so that every edge of two faces is run both ways (breadth first from each part's
// first face); an edge where that cannot hold is cut. Then a closed part that encloses negative
// volume, or an open part mostly turned, is turned back whole. Returns the faces turned.
std::vector<char> orient(const std::vector<Tri>& tris, const std::vector<Vec3>& x, std::set<std::pair<int32_t, int32_t>>& cut, int& parts) {
  const auto edges = edges_of(tris);
  std::vector<std::vector<std::pair<int, std::pair<int32_t, int32_t>>>> next(tris.size());
  for (const auto& [key, uses] : edges)
    if (uses.size() == 2) {
      next[static_cast<std::size_t>(uses[0].face)].push_back({uses[1].face, key});
      next[static_cast<std::size_t>(uses[1].face)].push_back({uses[0].face, key});
    } else if (uses.size() > 2) {
      cut.insert(key);
    }
  auto corner_of = [&](int f, const std::pair<int32_t, int32_t>& key) {
    for (const EdgeUse& u : edges.at(key))
      if (u.face == f) return u.corner;
    return 0;
  };
  std::vector<char> turned(tris.size(), 0), seen(tris.size(), 0);
  for (std::size_t start = 0; start < tris.size(); ++start) {
    if (seen[start]) continue;
    ++parts;
    std::vector<int> part{static_cast<int>(start)};
    std::deque<int> queue{static_cast<int>(start)};
    seen[start] = 1;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      for (const auto& [g, key] : next[static_cast<std::size_t>(f)]) {
        if (cut.count(key)) continue;
        const bool f_up = runs_up(tris[static_cast<std::size_t>(f)], corner_of(f, key)) != static_cast<bool>(turned[static_cast<std::size_t>(f)]);
        const bool g_up_as_is = runs_up(tris[static_cast<std::size_t>(g)], corner_of(g, key));
        const bool g_turned = g_up_as_is == f_up;  // g must run the edge the other way
        if (!seen[static_cast<std::size_t>(g)]) {
          seen[static_cast<std::size_t>(g)] = 1;
          turned[static_cast<std::size_t>(g)] = g_turned;
          part.push_back(g);
          queue.push_back(g);
        } else if (static_cast<bool>(turned[static_cast<std::size_t>(g)]) != g_turned) {
          cut.insert(key);
        }
      }
    }
    // The part's closedness and volume as wound now.
    std::map<std::pair<int32_t, int32_t>, int> count;
    double volume = 0;
    int turned_here = 0;
    for (int f : part) {
      Tri t = tris[static_cast<std::size_t>(f)];
      if (turned[static_cast<std::size_t>(f)]) std::swap(t[1], t[2]), ++turned_here;
      volume += x[static_cast<std::size_t>(t[0])].dot(x[static_cast<std::size_t>(t[1])].cross(x[static_cast<std::size_t>(t[2])]));
      for (int k = 0; k < 3; ++k) ++count[{std::min(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]), std::max(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)])}];
    }
    bool closed = true;
    for (const auto& [key, n] : count) closed = closed && n == 2 && !cut.count(key);
    const bool back = closed ? volume < 0 : 2 * turned_here > static_cast<int>(part.size());
    if (back)
      for (int f : part) turned[static_cast<std::size_t>(f)] = !turned[static_cast<std::size_t>(f)];
  }
  return turned;
}

}  // namespace

std::string SurfaceRepairs::summary() const {
  std::string out;
  auto say = [&](int n, const std::string& what) {
    if (n > 0) out += (out.empty() ? "" : ", ") + what + ": " + std::to_string(n);
  };
  say(dropped_faces, "faces without area or repeated, dropped");
  say(turned_faces, "faces turned to agree with their neighbours");
  say(cut_edges, "edges of three faces or more, cut open");
  say(copied_vertices, "vertices copied where separate sheets touch");
  say(open_edges, "edges on an open border");
  if (parts > 1) say(parts, "loose parts");
  return out;
}

RepairedSurface repair_surface(const MeshSource& surface) {
  for (std::size_t i = 0; i < surface.positions.size(); ++i)
    if (!surface.positions[i].allFinite()) throw MeshBuildError(-1, "position " + std::to_string(i + 1) + " is not finite");
  RepairedSurface out;
  SurfaceRepairs& r = out.repairs;
  const std::vector<int> kept = kept_faces(surface, r.dropped_faces);
  if (kept.empty()) throw MeshBuildError(-1, "no face with an area");
  std::vector<Tri> tris;
  for (int f : kept) {
    const auto& c = surface.faces[static_cast<std::size_t>(f)];
    tris.push_back({c[0].node, c[1].node, c[2].node});
  }
  std::set<std::pair<int32_t, int32_t>> cut;
  int parts_before = 0;
  const std::vector<char> turned = orient(tris, surface.positions, cut, parts_before);
  for (std::size_t f = 0; f < tris.size(); ++f)
    if (turned[f]) std::swap(tris[f][1], tris[f][2]), ++r.turned_faces;
  r.cut_edges = static_cast<int>(cut.size());

  // Around each position, the faces joined by edges that are not cut form its fans; each fan
  // after the first gets a copy of the position.
  const auto edges = edges_of(tris);
  Partition fans(tris.size() * 3);  // a face's corner
  for (const auto& [key, uses] : edges) {
    if (uses.size() != 2 || cut.count(key)) continue;
    const EdgeUse &u = uses[0], &v = uses[1];  // u runs a -> b, v runs b -> a
    fans.join(3 * u.face + u.corner, 3 * v.face + (v.corner + 1) % 3);
    fans.join(3 * u.face + (u.corner + 1) % 3, 3 * v.face + v.corner);
  }
  // The first fan of each position keeps it (the input's order kept, unused positions dropped);
  // the others get copies after all of them, in the order faces first use them.
  std::vector<int> first_fan(surface.positions.size(), -1);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (int& first = first_fan[static_cast<std::size_t>(tris[f][static_cast<std::size_t>(k)])]; first < 0) first = fans.find(static_cast<int>(3 * f) + k);
  std::map<int, int32_t> position_of_fan;
  for (std::size_t p = 0; p < first_fan.size(); ++p)
    if (first_fan[p] >= 0) {
      position_of_fan[first_fan[p]] = static_cast<int32_t>(out.source.size());
      out.source.push_back(static_cast<int32_t>(p));
    }
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t p = tris[f][static_cast<std::size_t>(k)];
      const auto [it, added] = position_of_fan.emplace(fans.find(static_cast<int>(3 * f) + k), static_cast<int32_t>(out.source.size()));
      if (added) {
        ++r.copied_vertices;
        out.source.push_back(p);
      }
      tris[f][static_cast<std::size_t>(k)] = it->second;
    }
  for (int32_t p : out.source) out.mesh.positions.push_back(surface.positions[static_cast<std::size_t>(p)]);

  // Faces two fans still join across a cut edge (both of its ends shared by other ways round)
  // stand alone.
  for (const auto& [key, uses] : edges_of(tris)) {
    const bool bad = uses.size() > 2 || (uses.size() == 2 && runs_up(tris[static_cast<std::size_t>(uses[0].face)], uses[0].corner) ==
                                                               runs_up(tris[static_cast<std::size_t>(uses[1].face)], uses[1].corner));
    if (!bad) continue;
    ++r.cut_edges;
    for (std::size_t i = 1; i < uses.size(); ++i)
      for (int32_t& p : tris[static_cast<std::size_t>(uses[i].face)]) {
        out.source.push_back(out.source[static_cast<std::size_t>(p)]);
        out.mesh.positions.push_back(out.mesh.positions[static_cast<std::size_t>(p)]);
        p = static_cast<int32_t>(out.source.size() - 1);
        ++r.copied_vertices;
      }
  }

  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto& c = surface.faces[static_cast<std::size_t>(kept[f])];
    std::array<Corner, 3> face{Corner{tris[f][0], c[0].uv}, Corner{tris[f][1], c[turned[f] ? 2 : 1].uv}, Corner{tris[f][2], c[turned[f] ? 1 : 2].uv}};
    out.mesh.faces.push_back(face);
  }
  out.mesh.uvs = surface.uvs;
  Partition pieces(tris.size());
  for (const auto& [key, uses] : edges_of(tris)) {
    if (uses.size() == 1) ++r.open_edges;
    for (const EdgeUse& u : uses) pieces.join(u.face, uses[0].face);
  }
  for (std::size_t f = 0; f < tris.size(); ++f) r.parts += pieces.find(static_cast<int>(f)) == static_cast<int>(f);
  return out;
}

ObstacleSurface build_obstacle_mesh(const MeshSource& surface) {
  RepairedSurface r = repair_surface(surface);
  with_canonical_uvs(r.mesh);
  return {build_mesh(r.mesh), std::move(r.source), r.repairs};
}

}  // namespace vdc
