// View factors (Koh et al. 2014, eqs. 3 and 4, section 3.3).
#include "view/view_factor.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace vdc {

namespace {

bool faces_camera(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c) {
  return area_normal(a, b, c).dot(frustum.eye - (a + b + c) / 3.0) > 0;
}

// The side the camera sees counts as the front: the outer side facing it, or the inner side
// where the depth image hides none of the corners and centre.
bool seen_as_front(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p, const DepthImage* depth) {
  if (faces_camera(frustum, a, b, c)) return true;
  if (depth == nullptr) return false;
  const double m = p.occlusion_depth;
  return !(depth->hidden(a, m) && depth->hidden(b, m) && depth->hidden(c, m) && depth->hidden((a + b + c) / 3.0, m));
}

// Eq. 3: from v_fb (in frame) down to v_out at `margin` from the frustum, linearly.
double factor_at(double distance, double v_fb, const ViewParams& p) {
  if (distance <= 0) return v_fb;
  if (distance >= p.margin) return p.v_out;
  return v_fb - distance / p.margin * (v_fb - p.v_out);
}

// How deep the face lies behind the occluders, 0 to 1: the fewest erosions at which any of its
// corners and centre is hidden, over the image's levels (an extension of eq. 3's ramp at the
// frustum to the outline of what hides the face).
double hidden_fraction(const DepthImage& depth, const Vec3& a, const Vec3& b, const Vec3& c, double margin) {
  int least = depth.levels();
  for (const Vec3& x : {a, b, c, Vec3((a + b + c) / 3.0)}) {
    least = std::min(least, depth.hidden_levels(x, margin));
    if (least == 0) break;
  }
  return static_cast<double>(least) / depth.levels();
}

}  // namespace

FaceView face_view(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p, const DepthImage* depth) {
  FaceView view;
  double v_fb = 1;
  if (p.occlusion && depth != nullptr) {
    const bool facing = faces_camera(frustum, a, b, c);
    view.hidden = hidden_fraction(*depth, a, b, c, p.occlusion_depth);
    view.front = facing || view.hidden == 0;
    v_fb = 1 - view.hidden * (1 - (facing ? p.v_occluded : p.v_back));
  } else {
    view.front = seen_as_front(frustum, a, b, c, p, depth);
    v_fb = view.front ? 1.0 : p.v_back;
  }
  view.distance = distance_to_frustum(frustum, a, b, c, p.margin);
  view.factor = factor_at(view.distance, v_fb, p);
  return view;
}

std::string camera_factor_attr(std::size_t camera, std::size_t count) {
  return count == 1 ? std::string(kViewFactorAttr) : std::string(kViewFactorAttr) + "_" + std::to_string(camera);
}

AnticipationWindow::AnticipationWindow(const CameraPath& path, double t, double frame_time, const ViewParams& p) {
  cameras.push_back(path.at(t));
  frusta.emplace_back(cameras.back());
  weights.push_back(1.0);
  offsets.push_back(0.0);
  const double ramp = p.anticipation * frame_time, lead = p.lead * frame_time, window = lead + ramp;
  if (window <= 0) return;
  std::vector<double> taus;
  const int n = std::max(1, static_cast<int>(std::ceil((p.lead + p.anticipation) * p.samples_per_frame)));
  for (int k = 1; k < n; ++k) taus.push_back(window * k / n);  // tau = L + T has weight 0
  for (double cut : path.cuts_in(t, t + window))
    if (cut < t + window) taus.push_back(cut - t);
  std::sort(taus.begin(), taus.end());
  for (double tau : taus) {
    cameras.push_back(path.at(t + tau));
    frusta.emplace_back(cameras.back());
    offsets.push_back(tau);
    weights.push_back(tau <= lead ? 1.0 : ramp > 0 ? 1 - (tau - lead) / ramp : 0.0);
  }
}

std::vector<DepthImage> occlusion_images(const AnticipationWindow& window, const OccluderDrawing& draw, const ViewParams& p, int threads) {
  if (!p.back_occlusion && !p.occlusion) return {};
  std::vector<std::optional<DepthImage>> made(window.cameras.size());
  const auto n = static_cast<int64_t>(made.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int64_t k = 0; k < n; ++k) {
    const auto at = static_cast<std::size_t>(k);
    made[at].emplace(window.cameras[at], p.occlusion_scale);
    draw(*made[at], window.offsets[at]);
    made[at]->erode(p.occlusion_erosion);
  }
  std::vector<DepthImage> images;
  images.reserve(made.size());
  for (auto& image : made) images.push_back(std::move(*image));
  return images;
}

double anticipated_view_factor(const AnticipationWindow& window, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p,
                               const std::vector<DepthImage>* depth, const std::array<Vec3, 3>* velocity) {
  double best = 0;
  for (std::size_t k = 0; k < window.frusta.size(); ++k) {
    const double w = window.weights[k];
    if (w <= best) break;  // later samples weigh less still
    // The face where its nodes' velocities take it by the sample's time (held where it is
    // without them).
    const double tau = velocity != nullptr ? window.offsets[k] : 0.0;
    const Vec3 ak = velocity != nullptr ? Vec3(a + tau * (*velocity)[0]) : a;
    const Vec3 bk = velocity != nullptr ? Vec3(b + tau * (*velocity)[1]) : b;
    const Vec3 ck = velocity != nullptr ? Vec3(c + tau * (*velocity)[2]) : c;
    // The factor at the planes' lower bound of the distance bounds it from above (eq. 3 is
    // linear in the distance between two values): a sample that cannot raise the best is not
    // measured exactly. The bound takes the face as facing the camera when it faces away: the
    // depth test is left for the samples that can raise the best.
    const Frustum& frustum = window.frusta[k];
    const bool front = faces_camera(frustum, ak, bk, ck) || depth != nullptr;
    const double d = frustum_plane_separation(frustum, ak, bk, ck);
    if (w * std::max(factor_at(d, front ? 1.0 : p.v_back, p), p.v_out) <= best) continue;
    best = std::max(best, w * face_view(frustum, ak, bk, ck, p, depth != nullptr ? &(*depth)[k] : nullptr).factor);
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
