// The prescribed camera: a perspective camera (pose, vertical field of view, image size in
// pixels, near and far planes) and a camera path of keyframes with smooth interpolation and
// cuts, evaluated at any time, future included (anticipation needs it).
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "core/math.hpp"
#include "core/track.hpp"

namespace vdc {

struct Camera {
  Vec3 position = Vec3(0, 0, 5);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3(0, 1, 0);
  double fov_y_degrees = 40;
  int width = 1920, height = 1080;  // pixels
  double near = 0.1, far = 100;     // m, along the view direction
  // Depth of field, a thin lens (focus_distance 0: a pinhole, everything sharp): the distance in
  // focus, the f-number, and the sensor's height, which with the field of view gives the focal
  // length.
  double focus_distance = 0;  // m, along the view direction
  // The focus follows the target (a focus puller on the subject): CameraPath::at sets
  // focus_distance to the target's distance at each time.
  bool focus_on_target = false;
  double f_stop = 2.8;
  double sensor_height_mm = 24;
  // Motion blur: how long the shutter is open, as a fraction of the frame time (0: no blur).
  double shutter = 0;
  // m along the camera's right vector: an eye of a parallel stereo rig (CameraPath::at moves
  // position and target by it), 0 for a camera at its keys.
  double eye_offset = 0;

  // Orthonormal view basis: right, true up, forward (towards the target).
  std::array<Vec3, 3> basis() const;
  double focal_pixels() const;  // pixels per unit of x/z at the image centre
  double focal_length_mm() const;  // the lens's focal length, from the sensor's height and the field of view
  // The diameter, in pixels, of the circle of confusion of a point at `depth` (m along the view
  // direction): A |depth - d| / depth * f / (d - f) on the sensor (A = f / N the aperture, d the
  // focus distance), in pixels of the image's height. 0 without depth of field.
  double blur_circle_pixels(double depth) const;
  // Pixel coordinates (x right, y down, origin at the top-left corner) and depth of x.
  Vec2 project(const Vec3& x, double* depth = nullptr) const;
  // Jacobian of project at x: pixels per metre, 2x3 (x must be in front of the camera).
  Mat23 projection_jacobian(const Vec3& x) const;
  // How many pixels a short length at x spans on screen at most (in the direction it looks
  // longest): the largest singular value of projection_jacobian(x).
  double pixels_per_metre(const Vec3& x) const;
  // The six planes bounding the view frustum, as inward unit normals n and offsets c, so that
  // n . x + c >= 0 inside.
  std::array<std::pair<Vec3, double>, 6> frustum_planes() const;
  // The eight corners of the frustum: near plane then far plane, each in the order
  // bottom-left, bottom-right, top-right, top-left.
  std::array<Vec3, 8> frustum_corners() const;
};

// A camera's projection to pixels with its basis and focal length worked out once, for many
// points: the same pixels and depths, bit for bit, as Camera::project.
struct Projection {
  explicit Projection(const Camera& camera);
  Vec2 operator()(const Vec3& x, double* depth = nullptr) const;
  std::array<Vec3, 3> basis;  // right, up, forward
  Vec3 position;
  double focal = 0, half_width = 0, half_height = 0;  // pixels
};

// A camera's view frustum, precomputed once for many faces.
struct Frustum {
  explicit Frustum(const Camera& camera);
  Vec3 eye;
  std::array<std::pair<Vec3, double>, 6> planes;  // inward unit normals and offsets
  std::array<Vec3, 8> corners;
};

// World-space distance from the triangle (a, b, c) to the view frustum: 0 when any part of it
// is inside. `cap`: distances of at least cap may be returned as cap (cheaper).
double distance_to_frustum(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c, double cap);
// The ball of `radius` around `centre` lies wholly outside the frustum, beyond one of its planes.
bool ball_outside(const Frustum& frustum, const Vec3& centre, double radius);
// A lower bound of that distance, cheap: how far the whole triangle lies beyond any one of the
// frustum's planes (0 if beyond none).
double frustum_plane_separation(const Frustum& frustum, const Vec3& a, const Vec3& b, const Vec3& c);

// One keyframe of a camera path. A key with `cut` starts a new shot: the path jumps to it
// with no interpolation from the key before.
struct CameraKey {
  double time = 0;
  Vec3 position = Vec3(0, 0, 5);
  Vec3 target = Vec3::Zero();
  bool cut = false;
  // The key's own up vector (the camera's roll) and vertical field of view (a zoom), as cameras
  // from animation packages have them; none: the lens's. A path where some key has one
  // interpolates it through every key (the lens's standing in for keys without).
  std::optional<Vec3> up = std::nullopt;
  std::optional<double> fov_y_degrees = std::nullopt;
};

// Euler angles in degrees (x, y, z) of a camera's orientation in Nuke's default rotation order
// ZXY: camera-to-world = Ry(y) Rx(x) Rz(z), the camera looking down its -z with +y up (so x is the
// pitch, y the heading, z the roll). Looking straight up or down, the roll is taken as 0.
Vec3 zxy_euler_degrees(const Camera& camera);
// The camera-to-world rotation of such angles: its columns are the camera's right, up and back.
Mat3 zxy_rotation(const Vec3& degrees);

class CameraPath {
 public:
  // `lens` gives the fixed parameters (up, field of view, image size, clip planes); keys sorted
  // by strictly increasing time, at least one.
  CameraPath(const Camera& lens, std::vector<CameraKey> keys);
  // The camera at time t: within a shot, position and target are interpolated smoothly (cubic
  // Hermite through the shot's keys); before the first key and after the last it holds. A stereo
  // eye (lens.eye_offset) is that camera moved sideways, its view direction kept.
  Camera at(double t) const;
  // Times of the cuts in (t0, t1].
  std::vector<double> cuts_in(double t0, double t1) const;
  const std::vector<CameraKey>& keys() const { return keys_; }
  const Camera& lens() const { return lens_; }

 private:
  Camera lens_;
  std::vector<CameraKey> keys_;
  struct Shot {
    double start;  // time of its first key (a cut), -infinity for the first shot
    Vec3Track position, target, up, fov;  // up and fov (in x) empty when no key has its own
  };
  std::vector<Shot> shots_;
};

}  // namespace vdc
