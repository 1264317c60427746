// Garments fitted to the figure that wears them: landmark heights and ease-keeping radii.
#include "scene/fitting.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/joint_names.hpp"

namespace vdc {

namespace {

int joint_or_throw(const Skeleton& skeleton, const std::string& name) {
  const std::optional<int> j = find_joint(skeleton, name);
  if (!j) throw std::invalid_argument(name);
  return *j;
}

Mat3 turn_about_y(double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitY()).toRotationMatrix(); }

}  // namespace

double FigureMeasure::girth_at(double y) const {
  const double k = std::floor((y - girth_base) / kGirthStep + 0.5);
  if (k < 0 || k >= static_cast<double>(girth.size())) return 0;
  return girth[static_cast<std::size_t>(k)];
}

FigureMeasure measure_figure(const Motion& motion, const Pose& pose, const std::vector<Vec3>& body, const std::vector<int>& main_joints,
                             double band) {
  const Skeleton& skeleton = motion.skeleton;
  const std::vector<Eigen::Isometry3d> world = motion.world(pose);
  FigureMeasure m;
  m.band = band;
  const Vec3 root = world.front().translation();
  m.axis = Vec3(root.x(), 0, root.z());
  const Vec3 forward = world.front().linear() * Vec3::UnitZ();
  if (std::hypot(forward.x(), forward.z()) > 1e-6) m.heading = std::atan2(forward.x(), forward.z());
  const Mat3 unturn = turn_about_y(-m.heading);
  auto local = [&](const Vec3& p) -> Vec3 { return unturn * (p - m.axis); };
  auto at = [&](const std::string& name) { return local(world[static_cast<std::size_t>(joint_or_throw(skeleton, name))].translation()); };

  double lowest = INFINITY;
  for (const auto& w : world) lowest = std::min(lowest, local(w.translation()).y());
  const Vec3 left_arm = at("LeftArm"), right_arm = at("RightArm");
  m.landmarks = {lowest, 0.5 * (at("LeftLeg").y() + at("RightLeg").y()), 0.5 * (at("LeftUpLeg").y() + at("RightUpLeg").y()),
                 0.5 * (left_arm.y() + right_arm.y()), at("Head").y()};
  for (std::size_t k = 1; k < m.landmarks.size(); ++k)
    if (!(m.landmarks[k] > m.landmarks[k - 1] + 0.01))
      throw std::invalid_argument("its soles, knees, hips, shoulders and head are not one above the other in the pose its garments are made in");
  m.shoulder_half_width = 0.5 * (std::hypot(left_arm.x(), left_arm.z()) + std::hypot(right_arm.x(), right_arm.z()));

  // Arms (from the collarbones, where the skeleton has them) and head are not what a garment's
  // rings go around.
  auto arm = [&](const std::string& shoulder, const std::string& arm_joint) {
    const std::optional<int> s = find_joint(skeleton, shoulder);
    return s ? *s : joint_or_throw(skeleton, arm_joint);
  };
  const int arms[] = {arm("LeftShoulder", "LeftArm"), arm("RightShoulder", "RightArm"), joint_or_throw(skeleton, "Head")};
  std::vector<char> left_out(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    for (int a : arms) left_out[j] = left_out[j] || descends_from(skeleton, static_cast<int>(j), a);
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3& x : body) {
    lo = std::min(lo, local(x).y());
    hi = std::max(hi, local(x).y());
  }
  if (body.empty()) return m;
  m.girth_base = lo - band;
  m.girth.assign(static_cast<std::size_t>(std::ceil((hi - lo + 2 * band) / FigureMeasure::kGirthStep)) + 1, 0.0);
  for (std::size_t v = 0; v < body.size(); ++v) {
    if (left_out[static_cast<std::size_t>(main_joints[v])]) continue;
    const Vec3 p = local(body[v]);
    const double r = std::hypot(p.x(), p.z());
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((p.y() - band - m.girth_base) / FigureMeasure::kGirthStep - 0.5)));
    const auto last = std::min(m.girth.size() - 1, static_cast<std::size_t>(std::floor((p.y() + band - m.girth_base) / FigureMeasure::kGirthStep + 0.5)));
    for (std::size_t k = first; k <= last; ++k) m.girth[k] = std::max(m.girth[k], r);
  }
  return m;
}

double FigureMeasure::reach_at(double y) const {
  const double k = std::floor((y - girth_base) / kGirthStep + 0.5);
  if (k < 0 || k >= static_cast<double>(reach.size())) return INFINITY;
  return reach[static_cast<std::size_t>(k)];
}

void measure_arm_reach(FigureMeasure& m, const Motion& motion, const Pose& pose, const std::vector<int>& main_joints,
                       const std::vector<Pose>& moving, const std::function<std::vector<Vec3>(const Pose&)>& skin) {
  const Skeleton& skeleton = motion.skeleton;
  const int arms[] = {joint_or_throw(skeleton, "LeftArm"), joint_or_throw(skeleton, "RightArm")};
  std::vector<char> arm(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    for (int a : arms) arm[j] = arm[j] || descends_from(skeleton, static_cast<int>(j), a);
  m.reach.assign(m.girth.size(), INFINITY);
  const double stand = motion.world(pose).front().translation().y();
  for (const Pose& p : moving) {
    const Eigen::Isometry3d root = motion.world(p).front();
    const Vec3 forward = root.linear() * Vec3::UnitZ();
    const Mat3 unturn = turn_about_y(std::hypot(forward.x(), forward.z()) > 1e-6 ? -std::atan2(forward.x(), forward.z()) : 0.0);
    const Vec3 axis(root.translation().x(), root.translation().y() - stand, root.translation().z());
    const std::vector<Vec3> x = skin(p);
    for (std::size_t v = 0; v < x.size(); ++v) {
      if (!arm[static_cast<std::size_t>(main_joints[v])]) continue;
      const Vec3 q = unturn * (x[v] - axis);
      const double r = std::hypot(q.x(), q.z());
      const double lo = std::ceil((q.y() - m.band - m.girth_base) / FigureMeasure::kGirthStep - 0.5);
      const double hi = std::floor((q.y() + m.band - m.girth_base) / FigureMeasure::kGirthStep + 0.5);
      for (double k = std::max(lo, 0.0); k <= std::min(hi, static_cast<double>(m.reach.size()) - 1); ++k)
        m.reach[static_cast<std::size_t>(k)] = std::min(m.reach[static_cast<std::size_t>(k)], r);
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

double GarmentFit::girth_change(double y) const { return figure_.girth_at(height(y)) - reference_.girth_at(y); }

double GarmentFit::largest_girth_change(double lo, double hi) const {
  double most = -INFINITY;
  for (double y = lo; y < hi; y += FigureMeasure::kGirthStep) most = std::max(most, girth_change(y));
  return std::max(most, girth_change(hi));
}

// The radius a garment needs at reference height y on the figure to keep `ease` times its ease
// there: the figure's girth at the matching height and that share of radius minus girth.
double GarmentFit::needed(double y, double radius, double ease) const {
  return figure_.girth_at(height(y)) + ease * (radius - reference_.girth_at(y));
}

TubeParams GarmentFit::fit(const TubeParams& p, double ease) const {
  TubeParams q = with_rows(p);
  // Both rings move out by what the tightest height needs.
  auto radius = [&](double y) { return p.bottom_radius + (y - p.bottom_height) / (p.top_height - p.bottom_height) * (p.top_radius - p.bottom_radius); };
  double wider = -INFINITY;
  for (double y = p.bottom_height; y < p.top_height; y += FigureMeasure::kGirthStep) wider = std::max(wider, needed(y, radius(y), ease) - radius(y));
  wider = std::max(wider, needed(p.top_height, p.top_radius, ease) - p.top_radius);
  q.top_height = height(p.top_height);
  q.bottom_height = height(p.bottom_height);
  q.top_radius = std::max(kNarrowest * p.top_radius, p.top_radius + wider);
  q.bottom_radius = std::max(kNarrowest * p.bottom_radius, p.bottom_radius + wider);
  return q;
}

DressParams GarmentFit::fit(const DressParams& p, double ease) const {
  DressParams q = with_rows(p);
  q.waist_height = height(p.waist_height);
  q.top_height = height(p.top_height);
  q.hem_height = height(p.hem_height);
  q.strap_rise = height(p.top_height + p.strap_rise) - q.top_height;
  double bodice = needed(p.top_height, p.bodice_radius, ease);
  for (double y = p.waist_height; y < p.top_height; y += FigureMeasure::kGirthStep) bodice = std::max(bodice, needed(y, p.bodice_radius, ease));
  q.bodice_radius = std::max(kNarrowest * p.bodice_radius, bodice);
  // The skirt is a cone from the bodice's radius at the waist: its hem is as wide as it must be
  // for the cone to keep, at every height, its share of the ease it has on the reference figure.
  q.hem_radius = std::max(q.bodice_radius + 0.5 * ease * (p.hem_radius - p.bodice_radius), needed(p.hem_height, p.hem_radius, ease));
  const double drop = p.waist_height - p.hem_height;
  for (double y = p.hem_height; y < p.waist_height; y += FigureMeasure::kGirthStep) {
    const double u = (p.waist_height - y) / drop;  // 0 at the waist, 1 at the hem
    if (u < 0.1) break;
    const double radius = needed(y, p.bodice_radius + u * (p.hem_radius - p.bodice_radius), ease);
    q.hem_radius = std::max(q.hem_radius, q.bodice_radius + (radius - q.bodice_radius) / u);
  }
  q.strap_x = std::min(0.8 * q.bodice_radius, p.strap_x * figure_.shoulder_half_width / reference_.shoulder_half_width);
  return q;
}

double GarmentFit::ease_clearing_arms(const std::vector<HeldGarment>& garments, double clearance) const {
  auto clear = [&](double ease) {
    for (const HeldGarment& g : garments) {
      if (g.held.empty()) continue;
      const MeshSource made = std::visit([&](const auto& p) { return make_garment(fit(p, ease)); }, g.pattern);
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
