// Procedural body: smooth union of tapered capsules (polynomial smooth minimum, Quilez) meshed
// by marching tetrahedra, with linear blend skinning (weights from the distance to each bone).
#include "scene/body.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "collision/distance.hpp"
#include "core/isosurface.hpp"

namespace vdc {

namespace {

struct Bone {
  int joint;     // the child joint: the bone runs from its parent to it
  Vec3 a, b;     // rest positions of the parent and child joints
  double ra, rb; // radii at a and b
};

bool has(const std::string& name, const char* word) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find(word) != std::string::npos;
}

// Radii at the two ends of the bone ending at joint `name`, for a figure of about 1.75 m.
std::pair<double, double> limb_radii(const std::string& name, const std::string& parent) {
  if (has(name, "head") || (has(name, "neck") && has(parent, "neck"))) return {0.09, 0.10};
  if (has(name, "neck")) return {0.06, 0.05};
  if (has(name, "spine") || has(name, "chest") || has(name, "back")) return {0.13, 0.14};
  if (has(name, "hipjoint") || (has(name, "hip") && !has(name, "hips"))) return {0.10, 0.09};
  if (has(name, "upleg") || has(name, "thigh")) return {0.09, 0.065};
  if (has(name, "toe")) return {0.035, 0.025};
  if (has(name, "foot") || has(name, "ankle")) return {0.045, 0.04};
  if (has(name, "leg") || has(name, "shin") || has(name, "knee")) return {0.065, 0.045};
  if (has(name, "shoulder") || has(name, "collar") || has(name, "clavicle")) return {0.06, 0.055};
  if (has(name, "forearm") || has(name, "elbow")) return {0.04, 0.032};
  if (has(name, "hand") || has(name, "wrist")) return {0.032, 0.028};
  if (has(name, "arm")) return {0.05, 0.04};
  if (has(name, "finger") || has(name, "thumb")) return {0.0, 0.0};  // part of the hand's blob
  return {0.04, 0.035};
}

double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

// Distance from p to the bone's tapered capsule surface (negative inside).
double capsule(const Bone& bone, const Vec3& p) {
  const Vec3 ab = bone.b - bone.a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - bone.a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (bone.a + t * ab)).norm() - ((1 - t) * bone.ra + t * bone.rb);
}

}  // namespace

Pose Body::rest_pose(const Skeleton& s) {
  Pose p;
  for (const Joint& j : s.joints) {
    p.rotation.push_back(Eigen::Quaterniond::Identity());
    p.translation.push_back(j.offset);
  }
  return p;
}

Body::Body(const Motion& motion, const BodyParams& params) : motion_(motion) {
  const auto& joints = motion.skeleton.joints;
  const std::vector<Eigen::Isometry3d> rest = motion.world(rest_pose(motion.skeleton));
  std::vector<Bone> bones;
  Aabb box;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const int parent = joints[j].parent;
    if (parent < 0) continue;
    auto [ra, rb] = limb_radii(joints[j].name, joints[static_cast<std::size_t>(parent)].name);
    if (ra <= 0) continue;
    Bone b{static_cast<int>(j), rest[static_cast<std::size_t>(parent)].translation(), rest[j].translation(), params.build * ra, params.build * rb};
    if ((b.b - b.a).norm() < 1e-6 && !has(joints[j].name, "head")) continue;
    bones.push_back(b);
    for (const Vec3& p : {b.a, b.b}) box.grow(p);
  }
  box.pad(0.2 * params.build + 2 * params.resolution);
  auto field = [&](const Vec3& p) {
    double d = 1e9;
    for (const Bone& b : bones) d = smooth_min(d, capsule(b, p), params.blend);
    return d;
  };
  rest_ = polygonize(field, box, params.resolution);
  with_canonical_uvs(rest_);

  // Skinning weights: each vertex follows the bones nearest to it (within the blend of the
  // nearest), weighted by 1 / (distance - nearest + blend)^4, at most four.
  influences_.resize(rest_.positions.size());
  for (std::size_t v = 0; v < rest_.positions.size(); ++v) {
    const Vec3& x = rest_.positions[v];
    std::vector<std::pair<double, int>> near;
    for (std::size_t b = 0; b < bones.size(); ++b) near.emplace_back(capsule(bones[b], x), static_cast<int>(b));
    std::sort(near.begin(), near.end());
    const double best = near.front().first;
    double total = 0;
    std::vector<std::pair<double, int>> picked;
    for (const auto& [d, b] : near) {
      if (picked.size() == 4 || d > best + 2 * params.blend) break;
      const double w = 1 / std::pow(d - best + 0.5 * params.blend, 4);
      picked.emplace_back(w, b);
      total += w;
    }
    for (const auto& [w, b] : picked) {
      // A bone from parent to child moves with the parent joint's transform.
      const int joint = joints[static_cast<std::size_t>(bones[static_cast<std::size_t>(b)].joint)].parent;
      const Eigen::Isometry3d& frame = rest[static_cast<std::size_t>(joint)];
      const Vec3 local = frame.inverse() * x;
      influences_[v].push_back(Influence{joint, w / total, local, frame * local});
    }
  }
}

std::vector<Vec3> Body::skin(const Pose& pose) const {
  const std::vector<Eigen::Isometry3d> world = motion_.world(pose);
  std::vector<Vec3> out(rest_.positions.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    // Displacement form: at the rest pose every term is exactly zero.
    Vec3 x = rest_.positions[v];
    for (const Influence& in : influences_[v]) x += in.weight * (world[static_cast<std::size_t>(in.joint)] * in.local - in.rest_world);
    out[v] = x;
  }
  return out;
}

}  // namespace vdc
