// View-dependent sizing (Koh, Narain and O'Brien, "View-Dependent Adaptive Cloth Simulation",
// SCA 2014, section 3): the camera's modification of the physical
// sizing field, plugged into compute_sizing as its FaceSizingModifier. evaluate() computes each
// face's view factor (eqs. 3 and 4, each face moved along its nodes' velocities over eq. 4's
// window unless motion_anticipation is off; with linger no faster fall than 1 / linger a frame
// from the factor the face had; then silhouette resampling); modify() scales the physical
// tensors by v^2 (eq. 2) but never below the velocity criterion, with keep_compression also
// Narain's compression criterion (what the camera does not see still has to move and gather as
// the seen cloth does), and, on faces visible now, bounds them in screen
// space so that no edge is asked to be shorter than l_min pixels (eqs. 5 to 8; with occlusion on
// every face in frame, hidden or turned away too) nor, when l_max
// is set, longer than l_max pixels (an extension: the visible cloth keeps the degrees of
// freedom its folds need). Before `settle` the view changes nothing: every factor is 1 and
// no screen-space bound applies, so a garment drops from its initial shape and finds its folds
// on the adaptive method's mesh (the folds that first form decide the shot's; a coarser mesh
// picks others). Where folds of fold_length are finer than the screen-space floor
// can show, it also tells compute_sizing how much coarser than those folds a face is
// (fold_coarsening), so that the compression law softens cloth that stands for them.
#pragma once
#include <optional>
#include <vector>

#include "remesh/sizing.hpp"
#include "view/view_factor.hpp"

namespace vdc {

// Eqs. 5 to 8: with S = J F (J the 2x3 projection Jacobian, F the 3x2 deformation gradient),
// S^T clamp(S^-T M S^-1, l_max^-2, l_min^-2) S, the clamp taken on eigenvalues; a bound of 0 is
// no bound. M is returned unchanged when S is singular or both bounds are 0.
Mat2 screen_space_bounds(const Mat2& m, const Mat23& projection_jacobian, const Mat32& deformation, double l_min, double l_max);

// How fully cloth whose folds span `fold_pixels` on screen is taken for folded below a
// screen-space floor of `floor_pixels`: 1 up to half the floor, falling linearly to 0 at the
// floor (and 0 without a floor), so that nothing jumps as the camera moves in.
double fold_weight(double fold_pixels, double floor_pixels);

struct ViewCounts {
  int visible = 0;       // in frame, outer side towards the camera
  int back_facing = 0;   // in frame, outer side away (and hidden, with occluders)
  int out_of_frame = 0;  // not in frame
  int hidden = 0;        // in frame, outer side towards the camera, behind something opaque (occlusion)
  int defocused = 0;     // visible, the screen-space floor set by the blur circle
  int blurred = 0;       // visible, the floor set by motion blur
};


class ViewSizing final : public FaceSizingModifier {
 public:
  ViewSizing(const CameraPath& path, const ViewParams& params, double time, double frame_time, int threads = 1);
  // View factors of the mesh's faces at the current positions and time (with linger, against
  // the mesh's kViewFactorAttr from the frame before, when it has one); `occluders`, when given
  // and not empty, are occlusion_images() of the same window (the back-face rule looks).
  void evaluate(const Mesh& mesh, const std::vector<DepthImage>* occluders = nullptr);
  // On the mesh evaluate() saw: its factors, and its visible faces' screen-space floors.
  void modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face_sizing) const override;
  // The screen-space floor, in pixels, of a visible face whose centre is at `centre` moving at
  // `velocity` now: l_min, raised to defocus_scale times its blur circle when the camera has
  // depth of field and to motion_blur_scale times how far its image moves while the shutter is
  // open when the camera has motion blur (the cloth's motion and the camera's; none across a cut).
  // `set_by`, when given: seen (l_min), defocused or motion_blurred.
  double screen_floor(const Vec3& centre, const Vec3& velocity, ViewReason* set_by = nullptr) const;
  // Folds finer than the image shows (an extension): on a face in frame where folds of
  // fold_length would span less than its screen-space floor, how much coarser than such folds
  // the face's final tensor lets it be (metric_ratio against fold_length^-2 I), weighted by
  // fold_weight; 0 where it is not weighted (out of frame, near the camera, fold_length 0).
  double fold_coarsening(const Mesh& mesh, FaceId f, const Mat2& sizing) const override;
  bool keeps_compression() const override { return params_.keep_compression; }
  const std::vector<double>& factors() const { return factor_; }  // by face index
  const std::vector<ViewReason>& reasons() const { return reason_; }  // by face index
  const ViewCounts& counts() const { return counts_; }

 private:
  double anticipated_factor(const Mesh& mesh, FaceId f, const AnticipationWindow& window, const std::vector<DepthImage>* occluders) const;
  const CameraPath& path_;
  ViewParams params_;
  double time_, frame_time_;
  int threads_;
  std::vector<double> factor_;
  std::vector<char> visible_;  // by face index: in frame and facing the camera now
  std::vector<char> floored_;  // by face index: under the screen-space floor (visible, or in frame with occlusion)
  std::vector<ViewReason> reason_;  // by face index
  std::vector<double> floor_;       // by face index: the screen-space floor of a visible face, pixels
  std::vector<double> fold_weight_;  // by face index: fold_weight of the face's folds on screen
  Camera now_;                 // the camera at time_
  std::optional<Camera> shutter_closes_;  // the camera when the shutter closes (motion blur)
  bool lens_blurs_ = false;               // depth of field or motion blur may raise the floor
  bool cut_ahead_ = false;                // a cut falls within eq. 4's window
  ViewCounts counts_;
};

}  // namespace vdc
