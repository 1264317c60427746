// View-dependent sizing field (Koh et al. 2014, eqs. 2 and 5 to 8).
#include "view/view_sizing.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

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

ViewSizing::ViewSizing(const CameraPath& path, const ViewParams& params, double time, double frame_time, int threads)
    : path_(path), params_(params), time_(time), frame_time_(frame_time), threads_(threads), now_(path.at(time)) {
  const double open = now_.shutter * frame_time;
  if (params_.motion_blur_scale > 0 && open > 0 && path.cuts_in(time, time + open).empty()) shutter_closes_ = path.at(time + open);
  lens_blurs_ = (params_.defocus_scale > 0 && now_.focus_distance > 0) || shutter_closes_.has_value();
  cut_ahead_ = !path.cuts_in(time, time + (params_.lead + params_.anticipation) * frame_time).empty();
}

// Detail finer than the image's blur does not show: the blur circle of a thin lens, and the
// streak of the face's image over the shutter's time (an extension of eqs. 5 to 8).
double ViewSizing::screen_floor(const Vec3& centre, const Vec3& velocity, ViewReason* set_by) const {
  double floor = params_.l_min;
  ViewReason by = ViewReason::seen;
  double depth = 0;
  const Vec2 at_open = now_.project(centre, &depth);
  if (depth > 0 && params_.defocus_scale > 0) {
    const double defocus = params_.defocus_scale * now_.blur_circle_pixels(depth);
    if (defocus > floor) floor = defocus, by = ViewReason::defocused;
  }
  if (depth > 0 && shutter_closes_) {
    double depth_closed = 0;
    const Vec2 at_close = shutter_closes_->project(centre + velocity * (now_.shutter * frame_time_), &depth_closed);
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

void ViewSizing::evaluate(const Mesh& mesh, const std::vector<DepthImage>* occluders) {
  factor_.assign(static_cast<std::size_t>(mesh.face_capacity()), 1.0);
  visible_.assign(factor_.size(), 0);
  floored_.assign(factor_.size(), 0);
  reason_.assign(factor_.size(), ViewReason::seen);
  floor_.assign(factor_.size(), params_.l_min);
  fold_weight_.assign(factor_.size(), 0.0);
  counts_ = ViewCounts{};
  const AnticipationWindow window(path_, time_, frame_time_, params_);
  if (occluders != nullptr && occluders->empty()) occluders = nullptr;
  if (occluders != nullptr && occluders->size() != window.cameras.size())
    throw std::logic_error("ViewSizing::evaluate: occlusion images of another window");
  const bool settling = params_.settling(time_);
  std::vector<FaceId> faces;
  for (FaceId f : mesh.faces()) faces.push_back(f);
  const auto n = static_cast<int64_t>(faces.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
  for (int64_t i = 0; i < n; ++i) {
    const FaceId f = faces[static_cast<std::size_t>(i)];
    const Vec3 &a = mesh.x(mesh.face_node(f, 0)), &b = mesh.x(mesh.face_node(f, 1)), &c = mesh.x(mesh.face_node(f, 2));
    const FaceView view = face_view(window.frusta.front(), a, b, c, params_, occluders != nullptr ? &occluders->front() : nullptr);
    const auto at = static_cast<std::size_t>(f.idx);
    // What the camera sees of the face now: seen, back_facing (turned away, or with occlusion
    // turned away and hidden), out_of_frame, or hidden (facing it behind something opaque).
    reason_[at] = view.distance > 0 ? ViewReason::out_of_frame
                  : view.hidden > 0 ? (view.front ? ViewReason::hidden : ViewReason::back_facing)
                  : view.front      ? ViewReason::seen
                                    : ViewReason::back_facing;
    visible_[at] = reason_[at] == ViewReason::seen;
    if (settling) continue;  // factor 1, no screen-space bound, no folds: the adaptive sizing
    factor_[at] = view.factor >= 1 ? 1.0 : anticipated_factor(mesh, f, window, occluders);
    // With occlusion or floor_in_frame, what is hidden or turned away in frame is no finer than
    // what is seen beside it: the screen-space floor bounds every face in frame (l_max only the
    // seen ones); but cloth a cut within the window will show better (eq. 4 raised its factor:
    // a cut to a close-up of it) is not floored by how small it looks before the cut. Without a
    // cut the camera's scale changes little over the window, and the floor holds.
    const bool shown_after_cut = cut_ahead_ && factor_[at] > view.factor;
    floored_[at] = visible_[at] ||
                   ((params_.occlusion || params_.floor_in_frame) && reason_[at] != ViewReason::out_of_frame && !shown_after_cut);
    if (lens_blurs_ && floored_[at]) {
      const Vec3 velocity = (mesh.v(mesh.face_node(f, 0)) + mesh.v(mesh.face_node(f, 1)) + mesh.v(mesh.face_node(f, 2))) / 3.0;
      ViewReason set_by = ViewReason::seen;
      floor_[at] = screen_floor((a + b + c) / 3.0, velocity, &set_by);
      if (visible_[at]) reason_[at] = set_by;
    }
    if (params_.fold_length > 0 && floor_[at] > 0 && reason_[at] != ViewReason::out_of_frame)
      fold_weight_[at] = fold_weight(params_.fold_length * now_.pixels_per_metre((a + b + c) / 3.0), floor_[at]);
  }
  for (FaceId f : faces) {
    const auto at = static_cast<std::size_t>(f.idx);
    counts_.visible += visible_[at];
    counts_.back_facing += reason_[at] == ViewReason::back_facing;
    counts_.out_of_frame += reason_[at] == ViewReason::out_of_frame;
    counts_.hidden += reason_[at] == ViewReason::hidden;
    counts_.defocused += reason_[at] == ViewReason::defocused;
    counts_.blurred += reason_[at] == ViewReason::motion_blurred;
  }
  // Eq. 4's ramp mirrored into the past (an extension): the factor the face had last frame
  // (the mesh's view_factor attribute, carried through remeshing) falls by at most 1 / linger.
  if (params_.linger > 0 && !settling && mesh.face_attrs().has(kViewFactorAttr)) {
    const auto& before = mesh.face_attrs().get<double>(kViewFactorAttr);
    for (FaceId f : faces) {
      const auto at = static_cast<std::size_t>(f.idx);
      factor_[at] = std::max(factor_[at], before[f] - 1.0 / params_.linger);
    }
  }
  resample_silhouettes(mesh, factor_, params_.silhouette_threshold);
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

void ViewSizing::modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face_sizing) const {
  for (FaceId f : mesh.faces()) {
    const double v = factor_[static_cast<std::size_t>(f.idx)];
    Mat2 m = v * v * face_sizing[f];  // eq. 2, on the shape only:
    if (v < 1) m = tensor_max(m, motion[static_cast<std::size_t>(f.idx)]);
    if (floored_[static_cast<std::size_t>(f.idx)] && (params_.l_min > 0 || params_.l_max > 0 || lens_blurs_)) {
      const auto& vs = mesh.face_verts(f);
      Mat2 du;
      du.col(0) = mesh.u(vs[1]) - mesh.u(vs[0]);
      du.col(1) = mesh.u(vs[2]) - mesh.u(vs[0]);
      Mat32 dx;
      const Vec3& x0 = mesh.x(mesh.face_node(f, 0));
      dx.col(0) = mesh.x(mesh.face_node(f, 1)) - x0;
      dx.col(1) = mesh.x(mesh.face_node(f, 2)) - x0;
      const Vec3 centre = (x0 + mesh.x(mesh.face_node(f, 1)) + mesh.x(mesh.face_node(f, 2))) / 3.0;
      const double l_min = floor_[static_cast<std::size_t>(f.idx)];  // evaluate()'s
      const double l_max = params_.l_max > 0 && visible_[static_cast<std::size_t>(f.idx)] ? std::max(params_.l_max, l_min) : 0.0;
      m = screen_space_bounds(m, now_.projection_jacobian(centre), dx * du.inverse(), l_min, l_max);
    }
    face_sizing[f] = m;
  }
}

}  // namespace vdc
