// Procedural body: smooth union of tapered capsules (polynomial smooth minimum, Quilez) meshed
// by marching tetrahedra, with linear blend skinning (weights from the distance to each bone).
#include "scene/body.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "collision/distance.hpp"
#include "core/isosurface.hpp"
#include "scene/joint_names.hpp"

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

// Radii at the two ends of the bone from joint `owner` to its child `child` (BVH: a joint's
// bone runs to its child), for a figure of about 1.75 m, by the usual joint names.
std::pair<double, double> limb_radii(const std::string& owner, const std::string& child) {
  if (has(owner, "finger") || has(owner, "thumb") || has(owner, "index") || has(child, "finger") || has(child, "thumb")) return {0, 0};
  if (has(owner, "head")) return {0.095, 0.09};
  if (has(owner, "neck")) return {0.05, 0.05};
  if (has(owner, "hipjoint") || ((has(owner, "hips") || has(owner, "pelvis") || has(owner, "root")) && (has(child, "upleg") || has(child, "hip") || has(child, "thigh"))))
    return {0.11, 0.09};
  if (has(owner, "hips") || has(owner, "pelvis") || has(owner, "root")) return {0.13, 0.13};
  if (has(owner, "spine") || has(owner, "chest") || has(owner, "back")) {
    if (has(child, "neck")) return {0.14, 0.07};
    if (has(child, "shoulder") || has(child, "collar") || has(child, "clavicle")) return {0.08, 0.06};
    return {0.13, 0.14};
  }
  if (has(owner, "shoulder") || has(owner, "collar") || has(owner, "clavicle")) return {0.06, 0.05};
  if (has(owner, "forearm")) return {0.04, 0.032};
  if (has(owner, "hand")) return {0.032, 0.025};
  if (has(owner, "upleg") || has(owner, "thigh")) return {0.085, 0.06};
  if (has(owner, "toe")) return {0.03, 0.025};
  if (has(owner, "foot") || has(owner, "ankle")) return {0.045, 0.035};
  if (has(owner, "leg") || has(owner, "shin") || has(owner, "knee")) return {0.06, 0.045};
  if (has(owner, "arm")) return {0.05, 0.04};
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

// The capsules of a skeleton's bones in a pose (world transforms of its joints), at `build`.
std::vector<Bone> bones_in(const Skeleton& skeleton, const std::vector<Eigen::Isometry3d>& world, double build) {
  std::vector<Bone> bones;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) continue;
    auto [ra, rb] = limb_radii(skeleton.joints[static_cast<std::size_t>(parent)].name, skeleton.joints[j].name);
    if (ra <= 0) continue;
    Bone b{static_cast<int>(j), world[static_cast<std::size_t>(parent)].translation(), world[j].translation(), build * ra, build * rb};
    if ((b.b - b.a).norm() < 1e-6) continue;
    bones.push_back(b);
  }
  return bones;
}

}  // namespace

double build_clearing_arms(const Motion& motion, const std::vector<Pose>& poses, double clearance) {
  const Skeleton& skeleton = motion.skeleton;
  std::vector<int> arms, shoulders_and_head;
  for (const char* side : {"Left", "Right"}) {
    const std::optional<int> arm = find_joint(skeleton, std::string(side) + "Arm");
    if (!arm) return 1.0;
    arms.push_back(*arm);
    const std::optional<int> shoulder = find_joint(skeleton, std::string(side) + "Shoulder");
    shoulders_and_head.push_back(shoulder ? *shoulder : *arm);
  }
  if (const std::optional<int> neck = find_joint(skeleton, "Neck")) shoulders_and_head.push_back(*neck);
  // Per joint: 1 an arm's, 2 a shoulder's, the neck's or the head's, 0 the torso's or a leg's.
  const std::vector<char> in_arm = joints_below(skeleton, arms), in_upper = joints_below(skeleton, shoulders_and_head);
  std::vector<int> part(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < part.size(); ++j) part[j] = in_arm[j] ? 1 : in_upper[j] ? 2 : 0;
  double build = 1.0;
  for (const Pose& pose : poses) {
    const std::vector<Bone> bones = bones_in(skeleton, motion.world(pose), 1.0);
    for (const Bone& arm : bones) {
      // A bone moves with its owner, the parent of the joint it runs to.
      if (part[static_cast<std::size_t>(skeleton.joints[static_cast<std::size_t>(arm.joint)].parent)] != 1) continue;
      for (const Bone& body : bones) {
        if (part[static_cast<std::size_t>(body.joint)] != 0) continue;  // a bone to a shoulder is the shoulder's
        // Capsule surfaces at build k are k (ra + rb) apart less than their axes: k = (d - c) / r.
        const Vec2 st = closest_segment_params(arm.a, arm.b, body.a, body.b);
        const double d = ((arm.a + st.x() * (arm.b - arm.a)) - (body.a + st.y() * (body.b - body.a))).norm();
        const double r = (1 - st.x()) * arm.ra + st.x() * arm.rb + (1 - st.y()) * body.ra + st.y() * body.rb;
        build = std::min(build, (d - clearance) / r);
      }
    }
  }
  return std::max(build, kSlimmestBuild);
}

Pose Body::rest_pose(const Skeleton& s) {
  Pose p;
  for (const Joint& j : s.joints) {
    p.rotation.push_back(Eigen::Quaterniond::Identity());
    p.translation.push_back(j.offset);
  }
  return p;
}

Body::Body(const Motion& motion, const BodyParams& params, BodyMeshCache* cache) : Body(motion, params, nullptr, cache) {}

Body::Body(const Motion& motion, const BodyParams& params, MeshSource skin) : Body(motion, params, &skin, nullptr) {}

Body::Body(const Motion& motion, const BodyParams& params, MeshSource* skin, BodyMeshCache* cache) : motion_(motion) {
  const auto& joints = motion.skeleton.joints;
  const std::vector<Eigen::Isometry3d> rest = motion.world(rest_pose(motion.skeleton));
  const std::vector<Bone> bones = bones_in(motion.skeleton, rest, params.build);
  Aabb box;
  for (const Bone& b : bones)
    for (const Vec3& p : {b.a, b.b}) box.grow(p);
  box.pad(0.2 * params.build + 2 * params.resolution);
  auto field = [&](const Vec3& p) {
    double d = 1e9;
    for (const Bone& b : bones) d = smooth_min(d, capsule(b, p), params.blend);
    return d;
  };
  if (skin) {
    rest_ = std::move(*skin);
  } else {
    // Everything the polygonization depends on.
    std::vector<double> key{params.resolution, params.blend, box.lo.x(), box.lo.y(), box.lo.z(), box.hi.x(), box.hi.y(), box.hi.z()};
    for (const Bone& b : bones) key.insert(key.end(), {b.a.x(), b.a.y(), b.a.z(), b.b.x(), b.b.y(), b.b.z(), b.ra, b.rb});
    const MeshSource* made = cache ? cache->find(key) : nullptr;
    rest_ = made ? *made : polygonize(field, box, params.resolution);
    if (cache && !made) cache->add(std::move(key), rest_);
  }
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
    main_joints_.push_back(std::max_element(influences_[v].begin(), influences_[v].end(), [](const Influence& a, const Influence& b) {
                             return a.weight < b.weight;
                           })->joint);
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
