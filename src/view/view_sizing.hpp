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


// The finer of two cameras' tensors: one that asks at least as much as the other in every
// direction, bit for bit (so that cameras asking the same, as every camera does while the drape
// settles, leave the physical tensor as it is: sizing takes any change for coarsening), else
// their tensor_max.
Mat2 finer_tensor(const Mat2& a, const Mat2& b);

// With several cameras (a shot filmed from more than one side, a stereo pair), each camera's
// factors, floors and folds are worked out as if it were the only one, and a face takes the most
// any camera asks of it: the largest factor (the deciding camera's reason beside it), and the
// finer_tensor of each camera's modified tensor, so that its screen-space floor is the finest any
// camera needs. A face out of every camera's frame is coarse; one that a single camera sees is
// as that camera alone would have it.
class ViewSizing final : public FaceSizingModifier {
 public:
  // `cameras`: the shot's cameras, at least one.
  ViewSizing(std::vector<const CameraPath*> cameras, const ViewParams& params, double time, double frame_time, int threads = 1);
  ViewSizing(const CameraPath& path, const ViewParams& params, double time, double frame_time, int threads = 1)
      : ViewSizing(std::vector<const CameraPath*>{&path}, params, time, frame_time, threads) {}
  // View factors of the mesh's faces at the current positions and time (with linger, against
  // each camera's factors from the frame before, the mesh's camera_factor_attr, when it has
  // them); `occluders`, when given, holds for each camera occlusion_images() of its window (the
  // back-face rule looks), or nothing.
  void evaluate(const Mesh& mesh, const std::vector<std::vector<DepthImage>>* occluders = nullptr);
  // On the mesh evaluate() saw: its factors, and its visible faces' screen-space floors.
  void modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face_sizing) const override;
  // The screen-space floor, in pixels, of a face visible to camera `camera` whose centre is at
  // `centre` moving at `velocity` now: l_min, raised to defocus_scale times its blur circle when
  // the camera has depth of field and to motion_blur_scale times how far its image moves while
  // the shutter is open when the camera has motion blur (the cloth's motion and the camera's;
  // none across a cut). `set_by`, when given: seen (l_min), defocused or motion_blurred.
  double screen_floor(const Vec3& centre, const Vec3& velocity, ViewReason* set_by = nullptr, std::size_t camera = 0) const;
  // Folds finer than the image shows (an extension): on a face in frame where folds of
  // fold_length would span less than its screen-space floor, how much coarser than such folds
  // the face's final tensor lets it be (metric_ratio against fold_length^-2 I), weighted by
  // fold_weight (the least of the cameras that have it in frame: folds any of them shows are
  // folds); 0 where it is not weighted (out of every frame, near a camera, fold_length 0).
  double fold_coarsening(const Mesh& mesh, FaceId f, const Mat2& sizing) const override;
  bool keeps_compression() const override { return params_.keep_compression; }
  const std::vector<double>& factors() const { return factor_; }  // by face index: the largest camera's
  const std::vector<ViewReason>& reasons() const { return reason_; }  // by face index: the deciding camera's
  const std::vector<int>& deciders() const { return decider_; }       // by face index: the deciding camera
  std::size_t cameras() const { return sights_.size(); }
  const std::vector<double>& camera_factors(std::size_t camera) const { return sights_.at(camera).factor; }  // by face index
  const ViewCounts& counts() const { return counts_; }

 private:
  // One camera's view of the mesh (all by face index but the camera's own state).
  struct Sight {
    const CameraPath* path = nullptr;
    Camera now;                             // the camera at time_
    std::optional<Camera> shutter_closes;  // the camera when the shutter closes (motion blur)
    bool lens_blurs = false;               // depth of field or motion blur may raise the floor
    bool cut_ahead = false;                // a cut falls within eq. 4's window
    std::vector<double> factor;
    std::vector<char> visible;        // in frame and facing the camera now
    std::vector<char> floored;        // under the screen-space floor (visible, or in frame with occlusion)
    std::vector<ViewReason> reason;
    std::vector<double> floor;        // the screen-space floor of a visible face, pixels
    std::vector<double> fold_weight;  // fold_weight of the face's folds on screen
  };
  // Eqs. 3 and 4 and the floors of face f for camera `camera` (writing only the face's entries).
  void see(const Mesh& mesh, FaceId f, std::size_t camera, const AnticipationWindow& window, const std::vector<DepthImage>* occluders,
           bool settling);
  double anticipated_factor(const Mesh& mesh, FaceId f, const AnticipationWindow& window, const std::vector<DepthImage>* occluders) const;
  // Eq. 2 and eqs. 5 to 8 for one camera: the tensor camera `sight` alone would give face f.
  Mat2 camera_tensor(const Mesh& mesh, FaceId f, const Sight& sight, const Mat2& physical, const Mat2& motion) const;
  // The faces' factors, reasons and folds from every camera's, and the counts.
  void decide(const std::vector<FaceId>& faces);
  ViewParams params_;
  double time_, frame_time_;
  int threads_;
  std::vector<Sight> sights_;
  std::vector<double> factor_;
  std::vector<ViewReason> reason_;
  std::vector<int> decider_;
  std::vector<double> fold_weight_;
  ViewCounts counts_;
};

}  // namespace vdc
