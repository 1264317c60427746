// Procedural garment patterns, sewn and placed around the figure in its rest pose.
#include "scene/garments.hpp"

#include <cmath>
#include <functional>

namespace vdc {

namespace {

// Builds pattern pieces into one MeshSource: each piece is a grid of world positions and
// material coordinates, whose nodes may be taken from pieces already added (seams).
class Sewing {
 public:
  // Adds a piece of (rows + 1) x (cols + 1) points. node(i, j) returns an existing node to share
  // or -1 for a new one at world(i, j); uv(i, j) is the material position. Faces are turned so
  // their world normal points along outward(point) and their material triangle is then
  // counter-clockwise (the piece's material layout is mirrored if needed).
  // With `wrap`, the last column is the first one again (a seam closing the piece into a tube).
  std::vector<std::vector<int32_t>> add_piece(int rows, int cols, bool wrap, const std::function<int32_t(int, int)>& node,
                                              const std::function<Vec3(int, int)>& world, const std::function<Vec2(int, int)>& uv,
                                              const std::function<Vec3(const Vec3&)>& outward) {
    std::vector<std::vector<int32_t>> nodes(static_cast<std::size_t>(rows + 1), std::vector<int32_t>(static_cast<std::size_t>(cols + 1)));
    std::vector<std::vector<int32_t>> uvs = nodes;
    for (int i = 0; i <= rows; ++i)
      for (int j = 0; j <= cols; ++j) {
        int32_t n = wrap && j == cols ? nodes[static_cast<std::size_t>(i)][0] : node(i, j);
        if (n < 0) {
          n = static_cast<int32_t>(src_.positions.size());
          src_.positions.push_back(world(i, j));
        }
        nodes[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = n;
        uvs[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = static_cast<int32_t>(src_.uvs.size());
        src_.uvs.push_back(uv(i, j));
      }
    const std::size_t first_uv = src_.uvs.size() - static_cast<std::size_t>((rows + 1) * (cols + 1));
    const std::size_t first_face = src_.faces.size();
    auto corner = [&](int i, int j) { return Corner{nodes[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)], uvs[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]}; };
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        for (auto tri : {std::array<Corner, 3>{corner(i, j), corner(i + 1, j), corner(i + 1, j + 1)},
                         std::array<Corner, 3>{corner(i, j), corner(i + 1, j + 1), corner(i, j + 1)}}) {
          const Vec3 &a = src_.positions[static_cast<std::size_t>(tri[0].node)], &b = src_.positions[static_cast<std::size_t>(tri[1].node)],
                     &c = src_.positions[static_cast<std::size_t>(tri[2].node)];
          if (area_normal(a, b, c).dot(outward((a + b + c) / 3.0)) < 0) std::swap(tri[1], tri[2]);
          src_.faces.push_back(tri);
        }
      }
    // The material layout must be counter-clockwise for these windings: mirror it if not.
    const auto& f = src_.faces[first_face];
    if (signed_area2(src_.uvs[static_cast<std::size_t>(f[0].uv)], src_.uvs[static_cast<std::size_t>(f[1].uv)],
                     src_.uvs[static_cast<std::size_t>(f[2].uv)]) < 0)
      for (std::size_t k = first_uv; k < src_.uvs.size(); ++k) src_.uvs[k].x() = -src_.uvs[k].x();
    return nodes;
  }
  MeshSource take() { return std::move(src_); }

 private:
  MeshSource src_;
};

// Rows of about `cell` over a length, at least `least`.
int rows_for(double length, double cell, int least) { return std::max(least, static_cast<int>(std::round(length / cell))); }

// The straps' half-ellipse from the bodice's top edge in front over the shoulder to the top edge
// behind, for a strap column whose front point is `f0`: its length.
double strap_path(const Vec3& f0, double rise) { return 0.5 * M_PI * std::sqrt(0.5 * (f0.z() * f0.z() + rise * rise)); }

// The strap column the left strap starts at (the one right of its centre line) and the ring
// point of a column on the bodice's top edge.
int first_strap_column(const DressParams& p) {
  const double centre_theta = 2 * M_PI + std::asin(p.strap_x / p.bodice_radius);  // front left
  return static_cast<int>(std::round((centre_theta - M_PI) * p.around / (2 * M_PI))) - 1;
}
Vec3 ring_point(const DressParams& p, double r, double y, int k) {
  const double theta = M_PI + 2 * M_PI * k / p.around;
  return Vec3(r * std::sin(theta), y, r * std::cos(theta));
}

// A tube around the figure's vertical axis from ring (top.y, top.r) down to ring (bottom.y,
// bottom.r), cut from its developed pattern (a rectangle, or an annular sector for a cone) and
// sewn at the back. With `sewn_top`, the top ring is those nodes. Returns the node rows, bottom
// (i = 0) to top.
std::vector<std::vector<int32_t>> add_tube(Sewing& sew, const TubeParams& p, const std::vector<int32_t>* sewn_top) {
  const int n = p.around;
  // Around the body from the back (z < 0) through the left side (+x) to the front and round.
  auto ring = [&](double r, double y, int k) {
    const double theta = M_PI + 2 * M_PI * k / n;
    return Vec3(r * std::sin(theta), y, r * std::cos(theta));
  };
  const double drop = p.top_height - p.bottom_height, flare = p.bottom_radius - p.top_radius, slant = std::hypot(drop, flare);
  const int rows = p.rows > 0 ? p.rows : rows_for(slant, p.cell, 1);
  // Row i from the bottom; in the pattern, a cone is developed about its apex.
  auto radius = [&](int i) { return p.bottom_radius - flare * i / rows; };
  const bool cone = std::abs(flare) > 1e-9 * slant;
  // The triangulated tube is a polygonal frustum (or prism), developable exactly: its ring
  // points lie at their distance from the apex, each face strip turning by the angle the
  // strip's chord subtends there.
  const double chord = 2 * p.top_radius * std::sin(M_PI / n);
  const double apex = cone ? p.top_radius * slant / flare : 0;  // apex to the top ring, along the slant (signed)
  const double turn = cone ? 2 * std::asin(0.5 * chord / apex) : 0;
  return sew.add_piece(
      rows, n, true,
      [&](int i, int k) { return sewn_top && i == rows ? (*sewn_top)[static_cast<std::size_t>(k)] : -1; },
      [&](int i, int k) { return ring(radius(i), p.bottom_height + drop * i / rows, k); },
      [&](int i, int k) {
        if (!cone) return Vec2(chord * k, slant * i / rows);
        const double r = apex + slant * (rows - i) / rows, b = turn * k;
        return Vec2(r * std::sin(b), -r * std::cos(b));
      },
      [](const Vec3& x) { return Vec3(x.x(), 0, x.z()); });
}

}  // namespace

MeshSource make_tube(const TubeParams& p) {
  Sewing sew;
  add_tube(sew, p, nullptr);
  return sew.take();
}

MeshSource make_dress(const DressParams& params) {
  const DressParams p = with_rows(params);
  Sewing sew;
  const int n = p.around;
  auto ring = [&](double r, double y, int k) { return ring_point(p, r, y, k); };
  const double column = 2 * p.bodice_radius * std::sin(M_PI / n);  // material width of a column (the ring's chord)

  // Bodice: a cylinder from the waist up to the top edge; skirt: a cone from the waist (sewn to
  // the bodice) down to the hem.
  const auto bodice = add_tube(sew, {p.around, p.top_height, p.bodice_radius, p.waist_height, p.bodice_radius, p.cell, p.bodice_rows}, nullptr);
  add_tube(sew, {p.around, p.waist_height, p.bodice_radius, p.hem_height, p.hem_radius, p.cell, p.skirt_rows}, &bodice[0]);
  const int rows_b = static_cast<int>(bodice.size()) - 1;

  // Straps: arcs over the shoulders from the top edge in front to the top edge behind, two
  // columns wide, each end sewn to the bodice's top row.
  const int first_left = first_strap_column(p);
  const auto& top = bodice[static_cast<std::size_t>(rows_b)];
  for (int side : {1, -1}) {
    // Front column c and the back column with the same x, mirrored through the x-y plane.
    auto front = [&](int c) { return side > 0 ? (first_left + c) % n : ((n - first_left - c) % n + n) % n; };
    auto back = [&](int c) { return ((n / 2 - front(c)) % n + n) % n; };
    const int rows = p.strap_rows;
    auto point = [&](int i, int c) {
      const Vec3 f = ring(p.bodice_radius, p.top_height, front(c));
      const double phi = M_PI * i / rows;
      return Vec3(f.x(), p.top_height + p.strap_rise * std::sin(phi), f.z() * std::cos(phi));
    };
    sew.add_piece(
        rows, 2, false,
        [&](int i, int c) {
          if (i == 0) return top[static_cast<std::size_t>(front(c))];
          if (i == rows) return top[static_cast<std::size_t>(back(c))];
          return -1;
        },
        point,
        [&](int i, int c) {
          double v = 0;  // arc length along this column
          for (int k = 1; k <= i; ++k) v += (point(k, c) - point(k - 1, c)).norm();
          return Vec2(column * c, v);
        },
        [&](const Vec3& x) { return Vec3(0, x.y() - p.top_height, x.z()); });
  }
  return sew.take();
}

TubeParams with_rows(TubeParams p) {
  if (p.rows <= 0) p.rows = rows_for(std::hypot(p.top_height - p.bottom_height, p.bottom_radius - p.top_radius), p.cell, 1);
  return p;
}

DressParams with_rows(DressParams p) {
  if (p.bodice_rows <= 0) p.bodice_rows = with_rows(TubeParams{p.around, p.top_height, p.bodice_radius, p.waist_height, p.bodice_radius, p.cell}).rows;
  if (p.skirt_rows <= 0) p.skirt_rows = with_rows(TubeParams{p.around, p.waist_height, p.bodice_radius, p.hem_height, p.hem_radius, p.cell}).rows;
  // Both straps are as long (mirror images): the left one's first column, the one after its start.
  if (p.strap_rows <= 0) {
    const Vec3 f0 = ring_point(p, p.bodice_radius, p.top_height, (first_strap_column(p) + 1) % p.around);
    p.strap_rows = rows_for(2 * strap_path(f0, p.strap_rise), p.cell, 2);
  }
  return p;
}

}  // namespace vdc
