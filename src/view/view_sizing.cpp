// View-dependent sizing field (Koh et al. 2014, eqs. 2 and 5 to 8).
#include "view/view_sizing.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vdc {

Mat2 screen_space_bounds(const Mat2& m, const Mat23& projection_jacobian, const Mat32& deformation, double l_min, double l_max) {
  if (!(l_min > 0) && !(l_max > 0)) return m;
  const Mat2 s = projection_jacobian * deformation;  // material metres -> pixels
  const double det = s.determinant();
  if (!(std::abs(det) > 1e-12 * s.squaredNorm()) || !std::isfinite(det)) return m;
  const Mat2 s_inv = s.inverse();
  const Mat2 screen = s_inv.transpose() * m * s_inv;  // eq. 5
  Eigen::SelfAdjointEigenSolver<Mat2> eig;
  eig.computeDirect(0.5 * (screen + screen.transpose()));  // eq. 6
  Vec2 clamped = eig.eigenvalues();
  if (l_min > 0) clamped = clamped.cwiseMin(1.0 / (l_min * l_min));  // eq. 7
  if (l_max > 0) clamped = clamped.cwiseMax(1.0 / (l_max * l_max));  // eq. 7's counterpart: no edge longer than l_max
  const Mat2 bounded = eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose();
  return s.transpose() * bounded * s;  // eq. 8
}

ViewSizing::ViewSizing(std::vector<const CameraPath*> cameras, const ViewParams& params, double time, double frame_time, int threads)
    : params_(params), time_(time), frame_time_(frame_time), threads_(threads) {
  if (cameras.empty()) throw std::logic_error("ViewSizing: a view needs a camera");
  for (const CameraPath* path : cameras) {
    Sight sight;
    sight.path = path;
    sight.now = path->at(time);
    const double open = sight.now.shutter * frame_time;
    if (params_.motion_blur_scale > 0 && open > 0 && path->cuts_in(time, time + open).empty()) sight.shutter_closes = path->at(time + open);
    sight.lens_blurs = (params_.defocus_scale > 0 && sight.now.focus_distance > 0) || sight.shutter_closes.has_value();
    sight.cut_ahead = !path->cuts_in(time, time + (params_.lead + params_.anticipation) * frame_time).empty();
    sights_.push_back(std::move(sight));
  }
}

// Detail finer than the image's blur does not show: the blur circle of a thin lens, and the
// streak of the face's image over the shutter's time (an extension of eqs. 5 to 8).
double ViewSizing::screen_floor(const Vec3& centre, const Vec3& velocity, ViewReason* set_by, std::size_t camera) const {
  const Sight& sight = sights_.at(camera);
  double floor = params_.l_min;
  ViewReason by = ViewReason::seen;
  double depth = 0;
  const Vec2 at_open = sight.now.project(centre, &depth);
  if (depth > 0 && params_.defocus_scale > 0) {
    const double defocus = params_.defocus_scale * sight.now.blur_circle_pixels(depth);
    if (defocus > floor) floor = defocus, by = ViewReason::defocused;
  }
  if (depth > 0 && sight.shutter_closes) {
    double depth_closed = 0;
    const Vec2 at_close = sight.shutter_closes->project(centre + velocity * (sight.now.shutter * frame_time_), &depth_closed);
    const double streak = depth_closed > 0 ? params_.motion_blur_scale * (at_close - at_open).norm() : 0.0;
    if (streak > floor) floor = streak, by = ViewReason::motion_blurred;
  }
  if (set_by) *set_by = by;
  return floor;
}

double ViewSizing::anticipated_factor(const Mesh& mesh, FaceId f, const AnticipationWindow& window, const std::vector<DepthImage>* occluders) const {
  const Vec3 &a = mesh.x(mesh.face_node(f, 0)), &b = mesh.x(mesh.face_node(f, 1)), &c = mesh.x(mesh.face_node(f, 2));
  if (!params_.motion_anticipation) return anticipated_view_factor(window, a, b, c, params_, occluders);
  const std::array<Vec3, 3> velocity = {mesh.v(mesh.face_node(f, 0)), mesh.v(mesh.face_node(f, 1)), mesh.v(mesh.face_node(f, 2))};
  return anticipated_view_factor(window, a, b, c, params_, occluders, &velocity);
}

void ViewSizing::see(const Mesh& mesh, FaceId f, std::size_t camera, const AnticipationWindow& window, const std::vector<DepthImage>* occluders,
                     bool settling) {
  Sight& sight = sights_[camera];
  const Vec3 &a = mesh.x(mesh.face_node(f, 0)), &b = mesh.x(mesh.face_node(f, 1)), &c = mesh.x(mesh.face_node(f, 2));
  const FaceView view = face_view(window.frusta.front(), a, b, c, params_, occluders != nullptr ? &occluders->front() : nullptr);
  const auto at = static_cast<std::size_t>(f.idx);
  // What the camera sees of the face now: seen, back_facing (turned away, or with occlusion
  // turned away and hidden), out_of_frame, or hidden (facing it behind something opaque).
  sight.reason[at] = view.distance > 0 ? ViewReason::out_of_frame
                     : view.hidden > 0 ? (view.front ? ViewReason::hidden : ViewReason::back_facing)
                     : view.front      ? ViewReason::seen
                                       : ViewReason::back_facing;
  sight.visible[at] = sight.reason[at] == ViewReason::seen;
  if (settling) return;  // factor 1, no screen-space bound, no folds: the adaptive sizing
  sight.factor[at] = view.factor >= 1 ? 1.0 : anticipated_factor(mesh, f, window, occluders);
  // With occlusion or floor_in_frame, what is hidden or turned away in frame is no finer than
  // what is seen beside it: the screen-space floor bounds every face in frame (l_max only the
  // seen ones); but cloth a cut within the window will show better (eq. 4 raised its factor:
  // a cut to a close-up of it) is not floored by how small it looks before the cut. Without a
  // cut the camera's scale changes little over the window, and the floor holds.
  const bool shown_after_cut = sight.cut_ahead && sight.factor[at] > view.factor;
  sight.floored[at] = sight.visible[at] || ((params_.occlusion || params_.floor_in_frame) && sight.reason[at] != ViewReason::out_of_frame &&
                                            !shown_after_cut);
  if (sight.lens_blurs && sight.floored[at]) {
    const Vec3 velocity = (mesh.v(mesh.face_node(f, 0)) + mesh.v(mesh.face_node(f, 1)) + mesh.v(mesh.face_node(f, 2))) / 3.0;
    ViewReason set_by = ViewReason::seen;
    sight.floor[at] = screen_floor((a + b + c) / 3.0, velocity, &set_by, camera);
    if (sight.visible[at]) sight.reason[at] = set_by;
  }
  if (params_.fold_length > 0 && sight.floor[at] > 0 && sight.reason[at] != ViewReason::out_of_frame)
    sight.fold_weight[at] = fold_weight(params_.fold_length * sight.now.pixels_per_metre((a + b + c) / 3.0), sight.floor[at]);
}

void ViewSizing::evaluate(const Mesh& mesh, const std::vector<std::vector<DepthImage>>* occluders) {
  const auto capacity = static_cast<std::size_t>(mesh.face_capacity());
  std::vector<AnticipationWindow> windows;
  if (occluders != nullptr && occluders->empty()) occluders = nullptr;
  if (occluders != nullptr && occluders->size() != sights_.size()) throw std::logic_error("ViewSizing::evaluate: occlusion images of other cameras");
  for (std::size_t k = 0; k < sights_.size(); ++k) {
    Sight& sight = sights_[k];
    sight.factor.assign(capacity, 1.0);
    sight.visible.assign(capacity, 0);
    sight.floored.assign(capacity, 0);
    sight.reason.assign(capacity, ViewReason::seen);
    sight.floor.assign(capacity, params_.l_min);
    sight.fold_weight.assign(capacity, 0.0);
    windows.emplace_back(*sight.path, time_, frame_time_, params_);
    if (occluders != nullptr && !(*occluders)[k].empty() && (*occluders)[k].size() != windows.back().cameras.size())
      throw std::logic_error("ViewSizing::evaluate: occlusion images of another window");
  }
  auto occluders_of = [&](std::size_t k) { return occluders != nullptr && !(*occluders)[k].empty() ? &(*occluders)[k] : nullptr; };
  const bool settling = params_.settling(time_);
  const std::vector<FaceId> faces = mesh.faces().list();
  const auto n = static_cast<int64_t>(faces.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
  for (int64_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < sights_.size(); ++k) see(mesh, faces[static_cast<std::size_t>(i)], k, windows[k], occluders_of(k), settling);
  for (std::size_t k = 0; k < sights_.size(); ++k) {
    std::vector<double>& factor = sights_[k].factor;
    // Eq. 4's ramp mirrored into the past (an extension): the factor the face had from this
    // camera last frame (a mesh attribute, carried through remeshing) falls by at most 1 / linger.
    const std::string before_attr = camera_factor_attr(k, sights_.size());
    if (params_.linger > 0 && !settling && mesh.face_attrs().has(before_attr)) {
      const auto& before = mesh.face_attrs().get<double>(before_attr);
      for (FaceId f : faces) {
        const auto at = static_cast<std::size_t>(f.idx);
        factor[at] = std::max(factor[at], before[f] - 1.0 / params_.linger);
      }
    }
    resample_silhouettes(mesh, factor, params_.silhouette_threshold);
  }
  decide(faces);
}

void ViewSizing::decide(const std::vector<FaceId>& faces) {
  const std::size_t capacity = sights_.front().factor.size();
  factor_.assign(capacity, 1.0);
  reason_.assign(capacity, ViewReason::seen);
  decider_.assign(capacity, 0);
  fold_weight_.assign(capacity, 0.0);
  counts_ = ViewCounts{};
  for (FaceId f : faces) {
    const auto at = static_cast<std::size_t>(f.idx);
    // The camera that asks the most of the face; of two that ask as much, one that sees it.
    std::size_t best = 0;
    for (std::size_t k = 1; k < sights_.size(); ++k) {
      const double mine = sights_[k].factor[at], kept = sights_[best].factor[at];
      if (mine > kept || (mine == kept && sights_[k].visible[at] && !sights_[best].visible[at])) best = k;
    }
    const Sight& by = sights_[best];
    decider_[at] = static_cast<int>(best);
    factor_[at] = by.factor[at];
    reason_[at] = by.reason[at];
    bool in_frame = false;
    for (const Sight& sight : sights_)
      if (sight.reason[at] != ViewReason::out_of_frame) {
        fold_weight_[at] = in_frame ? std::min(fold_weight_[at], sight.fold_weight[at]) : sight.fold_weight[at];
        in_frame = true;
      }
    counts_.visible += by.visible[at];
    counts_.back_facing += reason_[at] == ViewReason::back_facing;
    counts_.out_of_frame += reason_[at] == ViewReason::out_of_frame;
    counts_.hidden += reason_[at] == ViewReason::hidden;
    counts_.defocused += reason_[at] == ViewReason::defocused;
    counts_.blurred += reason_[at] == ViewReason::motion_blurred;
  }
}

double fold_weight(double fold_pixels, double floor_pixels) {
  if (!(floor_pixels > 0)) return 0.0;
  return std::clamp(2.0 * (1.0 - fold_pixels / floor_pixels), 0.0, 1.0);
}

double ViewSizing::fold_coarsening(const Mesh&, FaceId f, const Mat2& sizing) const {
  const auto at = static_cast<std::size_t>(f.idx);
  const double w = at < fold_weight_.size() ? fold_weight_[at] : 0.0;
  if (!(w > 0)) return 0.0;
  const double folds = metric_ratio(Mat2::Identity() / (params_.fold_length * params_.fold_length), sizing);
  return 1.0 + w * (folds - 1.0);
}

Mat2 ViewSizing::camera_tensor(const Mesh& mesh, FaceId f, const Sight& sight, const Mat2& physical, const Mat2& motion) const {
  const auto at = static_cast<std::size_t>(f.idx);
  const double v = sight.factor[at];
  Mat2 m = v * v * physical;  // eq. 2, on the shape only:
  if (v < 1) m = tensor_max(m, motion);
  if (!sight.floored[at] || !(params_.l_min > 0 || params_.l_max > 0 || sight.lens_blurs)) return m;
  const auto& vs = mesh.face_verts(f);
  Mat2 du;
  du.col(0) = mesh.u(vs[1]) - mesh.u(vs[0]);
  du.col(1) = mesh.u(vs[2]) - mesh.u(vs[0]);
  Mat32 dx;
  const Vec3& x0 = mesh.x(mesh.face_node(f, 0));
  dx.col(0) = mesh.x(mesh.face_node(f, 1)) - x0;
  dx.col(1) = mesh.x(mesh.face_node(f, 2)) - x0;
  const Vec3 centre = (x0 + mesh.x(mesh.face_node(f, 1)) + mesh.x(mesh.face_node(f, 2))) / 3.0;
  const double l_min = sight.floor[at];  // evaluate()'s
  const double l_max = params_.l_max > 0 && sight.visible[at] ? std::max(params_.l_max, l_min) : 0.0;
  return screen_space_bounds(m, sight.now.projection_jacobian(centre), dx * du.inverse(), l_min, l_max);
}

Mat2 finer_tensor(const Mat2& a, const Mat2& b) {
  const Mat2 d = b - a;  // symmetric: semidefinite when both diagonal entries share the sign of a non-negative determinant
  if (d.determinant() >= 0 && d(0, 0) <= 0 && d(1, 1) <= 0) return a;
  if (d.determinant() >= 0 && d(0, 0) >= 0 && d(1, 1) >= 0) return b;
  return tensor_max(a, b);
}

void ViewSizing::modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face_sizing) const {
  for (FaceId f : mesh.faces()) {
    const Mat2& physical = face_sizing[f];
    const Mat2& moving = motion[static_cast<std::size_t>(f.idx)];
    Mat2 m = camera_tensor(mesh, f, sights_.front(), physical, moving);
    for (std::size_t k = 1; k < sights_.size(); ++k) m = finer_tensor(m, camera_tensor(mesh, f, sights_[k], physical, moving));
    face_sizing[f] = m;
  }
}

}  // namespace vdc
