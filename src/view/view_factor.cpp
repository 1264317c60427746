// View factors (Koh et al. 2014, eqs. 3 and 4, section 3.3).
#include "view/view_factor.hpp"

#include <algorithm>
#include <cmath>

namespace vdc {

namespace {

bool faces_camera(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c) {
  return area_normal(a, b, c).dot(frustum.eye - (a + b + c) / 3.0) > 0;
}

// Eq. 3: from v_fb (in frame) down to v_out at `margin` from the frustum, linearly.
double factor_at(double distance, bool front, const ViewParams& p) {
  const double v_fb = front ? 1.0 : p.v_back;
  if (distance <= 0) return v_fb;
  if (distance >= p.margin) return p.v_out;
  return v_fb - distance / p.margin * (v_fb - p.v_out);
}

}  // namespace

FaceView face_view(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p) {
  FaceView view;
  view.front = faces_camera(frustum, a, b, c);
  view.distance = distance_to_frustum(frustum, a, b, c, p.margin);
  view.factor = factor_at(view.distance, view.front, p);
  return view;
}

AnticipationWindow::AnticipationWindow(const CameraPath& path, double t, double frame_time, const ViewParams& p) {
  frusta.emplace_back(path.at(t));
  weights.push_back(1.0);
  const double ramp = p.anticipation * frame_time, lead = p.lead * frame_time, window = lead + ramp;
  if (window <= 0) return;
  std::vector<double> taus;
  const int n = std::max(1, static_cast<int>(std::ceil((p.lead + p.anticipation) * p.samples_per_frame)));
  for (int k = 1; k < n; ++k) taus.push_back(window * k / n);  // tau = L + T has weight 0
  for (double cut : path.cuts_in(t, t + window))
    if (cut < t + window) taus.push_back(cut - t);
  std::sort(taus.begin(), taus.end());
  for (double tau : taus) {
    frusta.emplace_back(path.at(t + tau));
    weights.push_back(tau <= lead ? 1.0 : ramp > 0 ? 1 - (tau - lead) / ramp : 0.0);
  }
}

double anticipated_view_factor(const AnticipationWindow& window, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p) {
  double best = 0;
  for (std::size_t k = 0; k < window.frusta.size(); ++k) {
    const double w = window.weights[k];
    if (w <= best) break;  // later samples weigh less still
    // The factor at the planes' lower bound of the distance bounds it from above (eq. 3 is
    // linear in the distance between two values): a sample that cannot raise the best is not
    // measured exactly.
    const Frustum& frustum = window.frusta[k];
    const bool front = faces_camera(frustum, a, b, c);
    const double d = frustum_plane_separation(frustum, a, b, c);
    if (w * std::max(factor_at(d, front, p), p.v_out) <= best) continue;
    best = std::max(best, w * face_view(frustum, a, b, c, p).factor);
  }
  return best;
}

void resample_silhouettes(const Mesh& mesh, std::vector<double>& factor, double threshold) {
  std::vector<double> out = factor;
  for (EdgeId e : mesh.edges()) {
    const FaceId f0 = mesh.edge_face(e, 0), f1 = mesh.edge_face(e, 1);
    if (!f0.valid() || !f1.valid()) continue;
    const double v0 = factor[static_cast<std::size_t>(f0.idx)], v1 = factor[static_cast<std::size_t>(f1.idx)];
    if (std::abs(v0 - v1) <= threshold) continue;
    const FaceId lower = v0 < v1 ? f0 : f1;
    double& target = out[static_cast<std::size_t>(lower.idx)];
    target = std::max(target, 0.5 * (v0 + v1));
  }
  factor = std::move(out);
}

}  // namespace vdc
