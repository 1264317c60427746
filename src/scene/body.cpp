// Procedural body: smooth union of tapered capsules (polynomial smooth minimum, Quilez) meshed
// by marching tetrahedra, with linear blend skinning (weights from the distance to each bone).
#include "scene/body.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "collision/distance.hpp"
#include "core/isosurface.hpp"
#include "scene/humanoid.hpp"

namespace vdc {

namespace {

struct Bone {
  int joint;     // the child joint: the bone runs from its parent to it (or on to the limb's next joint)
  Vec3 a, b;     // positions of the parent joint and the joint the bone ends at
  double ra, rb; // radii at a and b
};

// Radii at the two ends of the bone from joint `owner` to its child (BVH: a joint's bone runs to
// its child) by their parts of the body, for a figure of about 1.75 m.
std::pair<double, double> limb_radii(BodyPart owner, BodyPart child, bool child_is_end_site) {
  using P = BodyPart;
  switch (owner) {
    case P::Finger: return {0, 0};
    case P::Hand: return child_is_end_site ? std::pair{0.032, 0.025} : std::pair{0.0, 0.0};  // to the fingers: theirs, none
    case P::Head: return {0.095, 0.09};
    case P::Neck: return {0.05, 0.05};
    case P::HipJoint: return {0.11, 0.09};
    case P::Hips: return child == P::HipJoint || child == P::Thigh ? std::pair{0.11, 0.09} : std::pair{0.13, 0.13};
    case P::Spine:
      if (child == P::Neck || child == P::Head) return {0.14, 0.07};
      if (child == P::Clavicle) return {0.08, 0.06};
      return {0.13, 0.14};
    case P::Clavicle: return {0.06, 0.05};
    case P::ForeArm: return {0.04, 0.032};
    case P::Thigh: return {0.085, 0.06};
    case P::Toe: return {0.03, 0.025};
    case P::Foot: return {0.045, 0.035};
    case P::Shin: return {0.06, 0.045};
    case P::UpperArm: return {0.05, 0.04};
    default: return {0.04, 0.035};
  }
}

// Every joint's part of the body, the order its bones are blended in (the smooth union depends
// on it) and where each bone ends: a humanoid's parts in the figure's order, so that its joints'
// names and order in the file change nothing, and one bone from a limb's joint to the next
// (shoulder to elbow, elbow to wrist, hip to knee, knee to ankle) past the joints that only
// twist it, which would bulge the union where two bones meet; else no parts, the file's order
// and a bone to every joint.
struct BodyPlan {
  std::vector<BodyPart> parts;
  std::vector<int> order;
  std::vector<int> bone_to;  // per joint: where the bone from its parent ends; -1 for none
};

// (`figure`: recognise_humanoid(skeleton).)
BodyPlan body_plan(const Skeleton& skeleton, const HumanoidRecognition& figure) {
  const std::size_t n = skeleton.joints.size();
  BodyPlan plan{std::vector<BodyPart>(n, BodyPart::Other), std::vector<int>(n), std::vector<int>(n)};
  for (std::size_t j = 0; j < n; ++j) plan.order[j] = plan.bone_to[j] = static_cast<int>(j);
  if (!figure.humanoid) return plan;
  const Humanoid& h = *figure.humanoid;
  plan.parts = h.parts;
  plan.order = figure_order(skeleton, h);
  std::vector<char> twists(n, 0);
  for (const auto* limbs : {&h.arms, &h.legs})
    for (const Limb& limb : *limbs)
      for (const auto& [from, to] : {std::pair{limb.root, limb.bend}, std::pair{limb.bend, limb.end}})
        for (int j = skeleton.joints[static_cast<std::size_t>(to)].parent; j != from; j = skeleton.joints[static_cast<std::size_t>(j)].parent) {
          twists[static_cast<std::size_t>(j)] = 1;
          if (skeleton.joints[static_cast<std::size_t>(j)].parent == from) plan.bone_to[static_cast<std::size_t>(j)] = to;
        }
  for (std::size_t j = 0; j < n; ++j)
    if (skeleton.joints[j].parent >= 0 && twists[static_cast<std::size_t>(skeleton.joints[j].parent)]) plan.bone_to[j] = -1;
  return plan;
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
std::vector<Bone> bones_in(const Skeleton& skeleton, const BodyPlan& plan, const std::vector<Eigen::Isometry3d>& world, double build) {
  std::vector<Bone> bones;
  for (const int joint : plan.order) {
    const auto j = static_cast<std::size_t>(joint);
    const int parent = skeleton.joints[j].parent, to = plan.bone_to[j];
    if (parent < 0 || to < 0) continue;
    auto [ra, rb] = limb_radii(plan.parts[static_cast<std::size_t>(parent)], plan.parts[j], skeleton.joints[j].end_site);
    if (ra <= 0) continue;
    Bone b{static_cast<int>(j), world[static_cast<std::size_t>(parent)].translation(), world[static_cast<std::size_t>(to)].translation(), build * ra,
           build * rb};
    if ((b.b - b.a).norm() < 1e-6) continue;
    bones.push_back(b);
  }
  return bones;
}

}  // namespace

double build_clearing_arms(const Motion& motion, const std::vector<Pose>& poses, double clearance) {
  const Skeleton& skeleton = motion.skeleton;
  const HumanoidRecognition figure = recognise_humanoid(skeleton);
  if (!figure.humanoid) return 1.0;
  const BodyPlan plan = body_plan(skeleton, figure);
  std::vector<int> arms, shoulders_and_head;
  for (const Limb& arm : figure.humanoid->arms) {
    arms.push_back(arm.root);
    shoulders_and_head.push_back(arm.girdle >= 0 ? arm.girdle : arm.root);
  }
  shoulders_and_head.push_back(figure.humanoid->neck >= 0 ? figure.humanoid->neck : figure.humanoid->head);
  // Per joint: 1 an arm's, 2 a shoulder's, the neck's or the head's, 0 the torso's or a leg's.
  const std::vector<char> in_arm = joints_below(skeleton, arms), in_upper = joints_below(skeleton, shoulders_and_head);
  std::vector<int> part(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < part.size(); ++j) part[j] = in_arm[j] ? 1 : in_upper[j] ? 2 : 0;
  double build = 1.0;
  for (const Pose& pose : poses) {
    const std::vector<Bone> bones = bones_in(skeleton, plan, motion.world(pose), 1.0);
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
  const std::vector<Bone> bones = bones_in(motion.skeleton, body_plan(motion.skeleton, recognise_humanoid(motion.skeleton)), rest, params.build);
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

Body::Body(const Motion& motion, Skin skin) : motion_(motion), rest_(std::move(skin.mesh)) {
  with_canonical_uvs(rest_);
  const std::vector<Eigen::Isometry3d> rest = motion.world(rest_pose(motion.skeleton));
  influences_.resize(rest_.positions.size());
  for (std::size_t v = 0; v < rest_.positions.size(); ++v) {
    Vec3 x = Vec3::Zero();
    for (const SkinWeight& w : skin.weights[v]) {
      const Vec3 rest_world = rest[static_cast<std::size_t>(w.joint)] * w.local;
      influences_[v].push_back(Influence{w.joint, w.weight, w.local, rest_world});
      x += w.weight * rest_world;
    }
    rest_.positions[v] = x;
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
