// Garments fitted to the figure that wears them: landmark heights and ease-keeping radii.
#include "scene/fitting.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/humanoid.hpp"

namespace vdc {

namespace {

Mat3 turn_about_y(double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitY()).toRotationMatrix(); }

// Where a root faces across the floor: radians about +y from +z (0 for a root facing up or down).
double heading(const Eigen::Isometry3d& root) {
  const Vec3 forward = root.linear() * Vec3::UnitZ();
  return std::hypot(forward.x(), forward.z()) > 1e-6 ? std::atan2(forward.x(), forward.z()) : 0.0;
}

// Calls visit(k, a, b) for every table height k (girth_base + k kGirthStep) whose horizontal plane
// cuts the triangle (p0, p1, p2), with the two points where the plane meets its edges.
template <class Visit>
void slice(const Vec3& p0, const Vec3& p1, const Vec3& p2, double base, std::size_t heights, Visit&& visit) {
  const double lo = std::min({p0.y(), p1.y(), p2.y()}), hi = std::max({p0.y(), p1.y(), p2.y()});
  const double step = FigureMeasure::kGirthStep;
  const double first = std::max(0.0, std::ceil((lo - base) / step)), last = std::min(static_cast<double>(heights) - 1, std::floor((hi - base) / step));
  const Vec3* corner[3] = {&p0, &p1, &p2};
  for (double k = first; k <= last; ++k) {
    const double y = base + k * step;
    Vec3 cut[2];
    int n = 0;
    for (int e = 0; e < 3 && n < 2; ++e) {
      const Vec3 &a = *corner[e], &b = *corner[(e + 1) % 3];
      if ((a.y() - y) * (b.y() - y) > 0 || a.y() == b.y()) continue;
      cut[n++] = a + (y - a.y()) / (b.y() - a.y()) * (b - a);
    }
    if (n == 2) visit(static_cast<std::size_t>(k), cut[0], cut[1]);
  }
}

// The nearest point of the horizontal segment (a, b) to the vertical axis: its distance.
double axis_distance(const Vec3& a, const Vec3& b) {
  const Vec2 p(a.x(), a.z()), q(b.x(), b.z()), d = q - p;
  const double t = d.squaredNorm() > 0 ? std::clamp(-p.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p + t * d).norm();
}

// Whether any corner of a face is moved most by one of `joints`.
bool touches(const std::array<Corner, 3>& face, const std::vector<int>& main_joints, const std::vector<char>& joints) {
  for (const Corner& c : face)
    if (joints[static_cast<std::size_t>(main_joints[static_cast<std::size_t>(c.node)])]) return true;
  return false;
}

}  // namespace

FigureMeasure measure_figure(const Motion& motion, const Pose& pose, const MeshSource& body_mesh, const std::vector<Vec3>& body,
                             const std::vector<int>& main_joints) {
  const Skeleton& skeleton = motion.skeleton;
  const std::vector<Eigen::Isometry3d> world = motion.world(pose);
  FigureMeasure m;
  const Vec3 root = world.front().translation();
  m.axis = Vec3(root.x(), 0, root.z());
  m.heading = heading(world.front());
  const Mat3 unturn = turn_about_y(-m.heading);
  auto local = [&](const Vec3& p) -> Vec3 { return unturn * (p - m.axis); };
  const Humanoid figure = humanoid_of(skeleton);
  auto at = [&](int joint) { return local(world[static_cast<std::size_t>(joint)].translation()); };

  double lowest = INFINITY;
  for (const auto& w : world) lowest = std::min(lowest, local(w.translation()).y());
  const Vec3 left_arm = at(figure.arms[0].root), right_arm = at(figure.arms[1].root);
  m.landmarks = {lowest, 0.5 * (at(figure.legs[0].bend).y() + at(figure.legs[1].bend).y()),
                 0.5 * (at(figure.legs[0].root).y() + at(figure.legs[1].root).y()), 0.5 * (left_arm.y() + right_arm.y()), at(figure.head).y()};
  for (std::size_t k = 1; k < m.landmarks.size(); ++k)
    if (!(m.landmarks[k] > m.landmarks[k - 1] + 0.01))
      throw std::invalid_argument("its soles, knees, hips, shoulders and head are not one above the other in the pose its garments are made in");
  m.shoulder_half_width = 0.5 * (std::hypot(left_arm.x(), left_arm.z()) + std::hypot(right_arm.x(), right_arm.z()));
  if (body.empty()) return m;

  // Arms (from the collarbones, where the skeleton has them) and head are not what a garment's
  // rings go around.
  auto arm = [&](const Limb& limb) { return limb.girdle >= 0 ? limb.girdle : limb.root; };
  const std::vector<char> left_out = joints_below(skeleton, {arm(figure.arms[0]), arm(figure.arms[1]), figure.head});
  std::vector<Vec3> x(body.size());
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t v = 0; v < body.size(); ++v) {
    x[v] = local(body[v]);
    lo = std::min(lo, x[v].y());
    hi = std::max(hi, x[v].y());
  }
  m.girth_base = lo;
  m.girth.assign(static_cast<std::size_t>(std::ceil((hi - lo) / FigureMeasure::kGirthStep)) + 1, 0.0);
  // The body's exact cross-section at each height: the farthest point of it is where the plane
  // cuts an edge (distance from the axis is convex along a segment).
  for (const auto& f : body_mesh.faces) {
    if (touches(f, main_joints, left_out)) continue;
    slice(x[static_cast<std::size_t>(f[0].node)], x[static_cast<std::size_t>(f[1].node)], x[static_cast<std::size_t>(f[2].node)], m.girth_base,
          m.girth.size(), [&](std::size_t k, const Vec3& a, const Vec3& b) {
            m.girth[k] = std::max({m.girth[k], std::hypot(a.x(), a.z()), std::hypot(b.x(), b.z())});
          });
  }
  return m;
}

double FigureMeasure::girth_at(double y) const {
  const double s = (y - girth_base) / kGirthStep;
  double g = 0;
  for (double k : {std::floor(s), std::ceil(s)})
    if (k >= 0 && k < static_cast<double>(girth.size())) g = std::max(g, girth[static_cast<std::size_t>(k)]);
  return g;
}

double FigureMeasure::reach_at(double y) const {
  const double s = (y - girth_base) / kGirthStep;
  double r = INFINITY;
  for (double k : {std::floor(s), std::ceil(s)})
    if (k >= 0 && k < static_cast<double>(reach.size())) r = std::min(r, reach[static_cast<std::size_t>(k)]);
  return r;
}

void measure_arm_reach(FigureMeasure& m, const Motion& motion, const Pose& pose, const MeshSource& body_mesh, const std::vector<int>& main_joints,
                       const std::vector<Pose>& moving, const std::function<std::vector<Vec3>(const Pose&)>& skin) {
  const Skeleton& skeleton = motion.skeleton;
  const Humanoid figure = humanoid_of(skeleton);
  const std::vector<char> arm = joints_below(skeleton, {figure.arms[0].root, figure.arms[1].root});
  std::vector<std::size_t> arm_faces;
  for (std::size_t f = 0; f < body_mesh.faces.size(); ++f)
    if (touches(body_mesh.faces[f], main_joints, arm)) arm_faces.push_back(f);
  m.reach.assign(m.girth.size(), INFINITY);
  const double stand = motion.world(pose).front().translation().y();
  for (const Pose& p : moving) {
    // Each pose in its own root's frame: the arms as the garments, which move with the body, meet them.
    const Eigen::Isometry3d root = motion.world(p).front();
    const Mat3 unturn = turn_about_y(-heading(root));
    const Vec3 axis(root.translation().x(), root.translation().y() - stand, root.translation().z());
    const std::vector<Vec3> x = skin(p);
    auto local = [&](int node) -> Vec3 { return unturn * (x[static_cast<std::size_t>(node)] - axis); };
    for (std::size_t f : arm_faces) {
      const auto& face = body_mesh.faces[f];
      slice(local(face[0].node), local(face[1].node), local(face[2].node), m.girth_base, m.reach.size(),
            [&](std::size_t k, const Vec3& a, const Vec3& b) { m.reach[k] = std::min(m.reach[k], axis_distance(a, b)); });
    }
  }
}

GarmentFit::GarmentFit(FigureMeasure reference, FigureMeasure figure) : reference_(std::move(reference)), figure_(std::move(figure)) {
  identity_ = std::abs(figure_.heading - reference_.heading) < 1e-9 && (figure_.axis - reference_.axis).norm() < 1e-6 &&
              std::abs(figure_.shoulder_half_width - reference_.shoulder_half_width) < 1e-6;
  for (std::size_t k = 0; k < reference_.landmarks.size(); ++k)
    identity_ = identity_ && std::abs(figure_.landmarks[k] - reference_.landmarks[k]) < 1e-6;
  for (double y = reference_.landmarks.front(); identity_ && y <= reference_.landmarks.back(); y += FigureMeasure::kGirthStep)
    identity_ = std::abs(figure_.girth_at(y) - reference_.girth_at(y)) < 2e-3;
}

double GarmentFit::height(double y) const {
  const auto& from = reference_.landmarks;
  const auto& to = figure_.landmarks;
  std::size_t i = 0;
  while (i + 2 < from.size() && y >= from[i + 1]) ++i;
  return to[i] + (y - from[i]) * (to[i + 1] - to[i]) / (from[i + 1] - from[i]);
}

std::optional<double> garment_radius(const TubeParams& tube, double y) {
  if (y < tube.bottom_height || y > tube.top_height) return std::nullopt;
  const double u = (tube.top_height - y) / (tube.top_height - tube.bottom_height);
  return tube.top_radius + u * (tube.bottom_radius - tube.top_radius);
}

std::optional<double> garment_radius(const DressParams& dress, double y) {
  if (y < dress.hem_height || y > dress.top_height) return std::nullopt;
  if (y >= dress.waist_height) return dress.bodice_radius;
  const double u = (dress.waist_height - y) / (dress.waist_height - dress.hem_height);
  return dress.bodice_radius + u * (dress.hem_radius - dress.bodice_radius);
}

std::optional<double> garment_radius(const GarmentPattern& pattern, double y) {
  return std::visit([y](const auto& p) { return garment_radius(p, y); }, pattern);
}

// The radius a garment needs at reference height y on the figure to keep `ease` times its ease
// there: the figure's girth at the matching height and that share of radius minus girth, and
// as much beyond each garment under it (of smaller radius there on the reference).
double GarmentFit::needed(double y, double radius, double ease, const std::vector<Under>& under) const {
  double need = figure_.girth_at(height(y)) + ease * (radius - reference_.girth_at(y));
  for (const Under& layer : under) {
    const std::optional<double> inner = garment_radius(*layer.reference, y);
    if (!inner || *inner >= radius) continue;
    if (const std::optional<double> fitted = garment_radius(*layer.fitted, height(y))) need = std::max(need, *fitted + ease * (radius - *inner));
  }
  return need;
}

TubeParams GarmentFit::fit(const TubeParams& p, double ease) const { return fit(p, ease, {}); }
DressParams GarmentFit::fit(const DressParams& p, double ease) const { return fit(p, ease, {}); }

std::vector<GarmentPattern> GarmentFit::fit(const std::vector<GarmentPattern>& worn, double ease) const {
  std::vector<GarmentPattern> fitted;
  for (const GarmentPattern& p : worn) fitted.push_back(std::visit([&](const auto& q) { return GarmentPattern(fit(q, ease)); }, p));
  // Each pass fits every garment over the others as the last pass fitted them: after as many
  // passes as there are garments, the deepest stack of layers has been carried outwards.
  for (std::size_t pass = 1; pass < worn.size(); ++pass) {
    std::vector<GarmentPattern> next;
    for (std::size_t g = 0; g < worn.size(); ++g) {
      std::vector<Under> under;
      for (std::size_t other = 0; other < worn.size(); ++other)
        if (other != g) under.push_back({&worn[other], &fitted[other]});
      next.push_back(std::visit([&](const auto& q) { return GarmentPattern(fit(q, ease, under)); }, worn[g]));
    }
    fitted = std::move(next);
  }
  return fitted;
}

TubeParams GarmentFit::fit(const TubeParams& p, double ease, const std::vector<Under>& under) const {
  TubeParams q = with_rows(p);
  q.top_height = height(p.top_height);
  q.bottom_height = height(p.bottom_height);
  // The top ring (where a tube hangs from, where a waistband is held) as close as its ease
  // allows; the bottom ring as wide as the cone then needs to keep its ease at every height.
  // (The cone's radius interpolated from the bottom up, as the fits in bench/RESULTS.md were
  // made; garment_radius's, from the top down, can differ in the last bit.)
  auto radius = [&](double y) { return p.bottom_radius + (y - p.bottom_height) / (p.top_height - p.bottom_height) * (p.top_radius - p.bottom_radius); };
  q.top_radius = std::max(kNarrowest * p.top_radius, needed(p.top_height, p.top_radius, ease, under));
  q.bottom_radius = std::max(kNarrowest * p.bottom_radius, needed(p.bottom_height, p.bottom_radius, ease, under));
  const double drop = p.top_height - p.bottom_height;
  for (double y = p.bottom_height; y < p.top_height; y += FigureMeasure::kGirthStep) {
    const double u = (p.top_height - y) / drop;  // 0 at the top, 1 at the bottom
    if (u < 0.1) break;
    q.bottom_radius = std::max(q.bottom_radius, q.top_radius + (needed(y, radius(y), ease, under) - q.top_radius) / u);
  }
  return q;
}

DressParams GarmentFit::fit(const DressParams& p, double ease, const std::vector<Under>& under) const {
  DressParams q = with_rows(p);
  q.waist_height = height(p.waist_height);
  q.top_height = height(p.top_height);
  q.hem_height = height(p.hem_height);
  q.strap_rise = height(p.top_height + p.strap_rise) - q.top_height;
  double bodice = needed(p.top_height, p.bodice_radius, ease, under);
  for (double y = p.waist_height; y < p.top_height; y += FigureMeasure::kGirthStep) bodice = std::max(bodice, needed(y, p.bodice_radius, ease, under));
  q.bodice_radius = std::max(kNarrowest * p.bodice_radius, bodice);
  // The skirt is a cone from the bodice's radius at the waist: its hem is as wide as it must be
  // for the cone to keep, at every height, its share of the ease it has on the reference figure.
  q.hem_radius = std::max(q.bodice_radius + 0.5 * ease * (p.hem_radius - p.bodice_radius), needed(p.hem_height, p.hem_radius, ease, under));
  const double drop = p.waist_height - p.hem_height;
  for (double y = p.hem_height; y < p.waist_height; y += FigureMeasure::kGirthStep) {
    const double u = (p.waist_height - y) / drop;  // 0 at the waist, 1 at the hem
    if (u < 0.1) break;
    const double radius = needed(y, *garment_radius(p, y), ease, under);
    q.hem_radius = std::max(q.hem_radius, q.bodice_radius + (radius - q.bodice_radius) / u);
  }
  q.strap_x = std::min(0.8 * q.bodice_radius, p.strap_x * figure_.shoulder_half_width / reference_.shoulder_half_width);
  return q;
}

double GarmentFit::ease_clearing_arms(const std::vector<HeldGarment>& garments, double clearance) const {
  std::vector<GarmentPattern> worn;
  for (const HeldGarment& g : garments) worn.push_back(g.pattern);
  auto clear = [&](double ease) {
    const std::vector<GarmentPattern> fitted = fit(worn, ease);
    for (std::size_t k = 0; k < garments.size(); ++k) {
      const HeldGarment& g = garments[k];
      if (g.held.empty()) continue;
      const MeshSource made = std::visit([](const auto& p) { return make_garment(p); }, fitted[k]);
      for (int n : g.held) {
        const Vec3& x = made.positions.at(static_cast<std::size_t>(n));
        if (std::hypot(x.x(), x.z()) > figure_.reach_at(x.y()) - clearance) return false;
      }
    }
    return true;
  };
  if (clear(1.0)) return 1.0;
  if (!clear(kLeastEase)) return kLeastEase;
  double lo = kLeastEase, hi = 1.0;  // clear at lo, not at hi
  for (int i = 0; i < 30; ++i) (clear(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

Vec3 GarmentFit::place(const Vec3& x) const { return turn_about_y(figure_.heading) * x + figure_.axis; }

}  // namespace vdc
