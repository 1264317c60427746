// View factors (Koh, Narain and O'Brien, "View-Dependent Adaptive Cloth Simulation", SCA 2014,
// sections 3.1 and 3.3): per face, how much of the physical resolution the camera needs.
// Spatial smoothing (eq. 3) by the distance to the view frustum, temporal smoothing with
// anticipation (eq. 4) over the camera's future, and silhouette resampling across edges where
// the factor jumps.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh.hpp"
#include "view/camera.hpp"
#include "view/depth_image.hpp"

namespace vdc {

// Face attribute (double) holding each face's view factor in view mode (Koh et al. 2014, eq. 4
// after silhouette resampling), carried through remeshing to the frame's output.
inline constexpr const char* kViewFactorAttr = "view_factor";
// Face attribute: what set the face's resolution at the last view evaluation (ViewReason).
inline constexpr const char* kViewReasonAttr = "view_reason";
// Face attribute of a shot with several cameras: the index of the camera whose factor the face
// took (the one that asks the most of it).
inline constexpr const char* kViewCameraAttr = "view_camera";
// The face attribute that keeps camera `camera`'s own factors between frames (for linger), of a
// shot with `count` cameras: kViewFactorAttr itself when there is one.
std::string camera_factor_attr(std::size_t camera, std::size_t count);
// Why a face has the resolution it has: seen (the screen-space floor l_min), turned away, out of
// frame, seen but its floor set by the lens's blur circle, or by motion blur, or hidden behind
// something opaque (ViewParams::occlusion).
enum class ViewReason : char { seen = 0, back_facing = 1, out_of_frame = 2, defocused = 3, motion_blurred = 4, hidden = 5 };

struct ViewParams {
  double v_back = 0.2;                // factor of in-frame faces whose outer side faces away
  double v_out = 0.01;                // factor of faces farther than the margin from the frustum
  double margin = 0.4;                // m: the fall-off from the frustum to v_out
  double anticipation = 5;            // frames: T, how far ahead the camera is looked at
  // frames: cloth to be seen within this time is at the resolution it will be seen at (weight
  // 1); the window's weights then fall over the `anticipation` frames after it (0: eq. 4)
  double lead = 0;
  // frames: a face the camera stops needing coarsens over this time instead of at once, its
  // factor falling by at most 1 / linger a frame from the one it had (eq. 4's ramp mirrored
  // into the past): cloth turning away beside the seen cloth does not swap resolution with every
  // turn (0: at once, as in the paper)
  double linger = 0;
  double l_min = 4;                   // pixels: shortest visible edge on screen (0: no floor)
  double l_max = 0;                   // pixels: longest visible edge on screen (0: no ceiling)
  double silhouette_threshold = 0.5;  // factor jump across an edge that triggers resampling
  int samples_per_frame = 4;          // camera samples per frame over the anticipation window
  double settle = 0;                  // s: before this time the view changes no sizing (the drape forms as in adaptive)
  // Whether a frame starting at `time` is still sized as in adaptive mode (frame start times
  // are sums of frame_time, hence the nanosecond), and how many frames from the shot's start
  // are (a count held as a double: settle may be any length).
  bool settling(double time) const { return time + 1e-9 < settle; }
  double settle_frames(double frame_time) const { return std::max(0.0, std::ceil((settle - 1e-9) / frame_time)); }
  // A face turned away from the camera takes v_back only where something hides it: its corners
  // and centre all behind a depth image of the bodies and garments (otherwise it is the inside
  // of a garment in plain view, and counts as facing the camera). false: the seed's rule.
  bool back_occlusion = false;
  double occlusion_scale = 0.125;  // the depth images' size relative to the camera's image
  int occlusion_erosion = 1;       // pixels of a depth image: an occluder's edge hides nothing this near it
  double occlusion_depth = 0.02;   // m: how far behind the nearest surface a point must lie to be hidden
  // A face in frame whose corners and centre all lie behind the depth images (bodies and opaque
  // garments, at the window's sample times) takes v_occluded, turned away v_back, ramping to 1
  // over the occlusion_erosion pixels inside the occluder's outline; a face turned away that
  // nothing hides is the inside of a garment in view and counts as facing the camera.
  bool occlusion = false;
  double v_occluded = 0.2;  // factor of hidden faces that face the camera (a scene's default: its v_back)
  // The screen-space floor (l_min, and the lens's) bounds every face in frame, turned away or
  // hidden too, not only the faces seen: no cloth in frame is finer than the cloth seen beside
  // it, whatever its motion asks (always so with occlusion), unless a cut within eq. 4's window
  // will show it better (eq. 4 raised its factor).
  bool floor_in_frame = false;
  // m: the width of the folds cloth forms where nothing holds it smooth (an extension). A smooth
  // coarse mesh cannot show or form them, and its physical sizing, measured on that smooth
  // mesh, does not ask for them either, so by the physical sizing alone it stays a stiff cone
  // where the adaptive cloth gathers into folds. On a face in frame where folds this wide
  // would span less than half the screen-space floor (a far dancer), the compression law
  // (membrane.hpp) measures the face's coarsening against these folds too; it fades out as
  // they grow to the whole floor on screen. 0: off.
  double fold_length = 0.02;
  // s: where those folds set a face's coarsening, its compression factor softens to the law's
  // over this time rather than at once, as the folds take time to form (0: at once).
  double fold_time = 0.4;
  // A coarse face remembers the gathering (compressive strain) it was made with and resists
  // being gathered further with this strain factor (membrane.hpp; its stiffness the square),
  // where the compression law alone lets it collapse at almost no cost (an extension). 0: off.
  double gathering = 0;
  // Coarse faces softened by the compression law dissipate as the folds they stand for would:
  // Rayleigh damping of their membrane, in multiples of the time step (StepParams::
  // coarse_damping; an extension). 0: off.
  double coarse_damping = 0;
  // The motion criterion that eq. 2 never scales a coarse face below includes Narain's
  // compression criterion (where the face is not pressed between two surfaces), not velocity
  // alone: cloth the camera turned away from keeps the resolution of the buckles it is about to
  // form, and the visible cloth beside it gathers as in the adaptive run (an extension).
  bool keep_compression = false;
  // Eq. 4 moves each face along its nodes' velocities to each sample's time (the cloth's own
  // motion anticipated to first order) rather than holding it where it is.
  bool motion_anticipation = true;
  // The screen-space floor (l_min) of a visible face grows to this multiple of its blur circle
  // when the camera has depth of field, and of how far its image moves while the shutter is
  // open when the camera has motion blur: detail finer than the blur does not show. 0: off.
  double defocus_scale = 1;
  double motion_blur_scale = 1;
  // Physics level of detail (an extension): a garment group whose cloth no camera resolves over
  // the coming frames (level_of_detail.hpp: its folds of fold_length under half of l_min on
  // screen wherever it can be in frame, and no edge it may have past l_max) is sized and remeshed
  // only on every far_remesh_every-th frame; the frames between keep its mesh. 1: every frame.
  int far_remesh_every = 1;
  // s: not before this time. A dress dropping into its drape refines as its folds form, and a
  // mesh that waits frames for them drapes elsewhere (crowd-100's sample: overlap 0.854 against
  // 0.888 from frame 0, 0.886 from 1 s on).
  double far_after = 1;
};

// How a face is seen at one instant.
struct FaceView {
  double distance = 0;  // m, to the view frustum (0: in frame)
  bool front = true;    // its outer side faces the camera (or its inner side is seen)
  double hidden = 0;    // with occlusion: 0 in plain view, 1 hidden beyond the erosion, the ramp between
  double factor = 1;    // eq. 3
};

// Eq. 3 for the triangle (a, b, c), counter-clockwise seen from its outer side. With `depth` (the
// scene seen by the frustum's camera), a face turned away counts as facing the camera unless
// the depth image hides it (ViewParams::back_occlusion), and with ViewParams::occlusion a face
// the depth image hides takes v_occluded (v_back if turned away) over the ramp.
FaceView face_view(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p,
                   const DepthImage* depth = nullptr);

// The camera over the anticipation window [t, t + L + T] (L the lead): frusta at offsets tau,
// increasing, with their weights w(tau) = 1 up to L, then 1 - (tau - L) / T (eq. 4 when L = 0);
// sampled `samples_per_frame` times a frame and at every cut in the window (the first instant of
// the new shot), so a cut is never missed.
struct AnticipationWindow {
  AnticipationWindow(const CameraPath& path, double t, double frame_time, const ViewParams& p);
  std::vector<Camera> cameras;  // cameras[0] is the camera now
  std::vector<Frustum> frusta;  // of the cameras
  std::vector<double> weights;  // weights[0] = 1
  std::vector<double> offsets;  // s: the samples' times after t, offsets[0] = 0
};

// Draws into `image` (a camera of the window, nothing drawn yet) the scene's opaque triangles,
// bodies and garments, where they are `tau` seconds after the window's start.
using OccluderDrawing = std::function<void(DepthImage& image, double tau)>;

// The depth images of what `draw` draws from each of the window's cameras at that camera's time
// (called side by side from the threads), eroded; empty unless p.back_occlusion or p.occlusion.
std::vector<DepthImage> occlusion_images(const AnticipationWindow& window, const OccluderDrawing& draw, const ViewParams& p, int threads = 1);

// Eq. 4: v(t) = max over tau of w(tau) v~(t + tau), the face held where it is; `depth`, when
// given, holds occlusion_images(window, ...) (one image a camera).
// With `velocity` (the corners'), the face is moved along it to each sample's time instead.
double anticipated_view_factor(const AnticipationWindow& window, const Vec3& a, const Vec3& b, const Vec3& c, const ViewParams& p,
                               const std::vector<DepthImage>* depth = nullptr, const std::array<Vec3, 3>* velocity = nullptr);

// Section 3.3: across every edge where the factors of its two faces differ by more than the
// threshold, the less visible face takes their average (the larger such average if it has
// several); faces at 1 never change. `factor` is indexed by face index.
void resample_silhouettes(const Mesh& mesh, std::vector<double>& factor, double threshold);

}  // namespace vdc
