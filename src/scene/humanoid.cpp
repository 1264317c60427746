// Humanoid skeletons recognised by their tree and rest pose.
#include "scene/humanoid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "scene/joint_names.hpp"

namespace vdc {

namespace {

// The skeleton's tree and rest pose (every joint's rotation the identity) as the search reads them.
struct Shape {
  const Skeleton& skeleton;
  std::vector<Vec3> at;                  // rest positions
  std::vector<std::vector<int>> children;  // per joint: its children, end sites included
  std::vector<std::vector<int>> limbs;   // per joint: its children that are joints, not end sites
  std::vector<double> extent;            // per joint: the farthest any joint below it is from it

  explicit Shape(const Skeleton& s)
      : skeleton(s), at(s.joints.size()), children(s.joints.size()), limbs(s.joints.size()), extent(s.joints.size(), 0.0) {
    for (std::size_t j = 0; j < s.joints.size(); ++j) {
      const int parent = s.joints[j].parent;
      at[j] = parent < 0 ? s.joints[j].offset : at[static_cast<std::size_t>(parent)] + s.joints[j].offset;
      if (parent >= 0) children[static_cast<std::size_t>(parent)].push_back(static_cast<int>(j));
      if (parent >= 0 && !s.joints[j].end_site) limbs[static_cast<std::size_t>(parent)].push_back(static_cast<int>(j));
    }
    // Every joint's distance to each of its ancestors: O(joints x depth), the depth bounded by the reader.
    for (std::size_t j = 0; j < s.joints.size(); ++j)
      for (int a = s.joints[j].parent; a >= 0; a = s.joints[static_cast<std::size_t>(a)].parent)
        extent[static_cast<std::size_t>(a)] = std::max(extent[static_cast<std::size_t>(a)], (at[j] - at[static_cast<std::size_t>(a)]).norm());
  }
  const Vec3& p(int j) const { return at[static_cast<std::size_t>(j)]; }
  double reach(int j) const { return extent[static_cast<std::size_t>(j)]; }
  int parent(int j) const { return skeleton.joints[static_cast<std::size_t>(j)].parent; }
  // How far the subtree of `child` reaches from its parent (an upper bound: the bone and its extent).
  double reach_from_parent(int child) const { return (p(child) - p(parent(child))).norm() + reach(child); }

  // The limb's main chain from `first`: at each joint on to the child reaching farthest, to a joint
  // with no children but end sites.
  std::vector<int> chain(int first) const {
    std::vector<int> out{first};
    for (;;) {
      const std::vector<int>& next = limbs[static_cast<std::size_t>(out.back())];
      if (next.empty()) return out;
      out.push_back(*std::max_element(next.begin(), next.end(), [&](int a, int b) { return reach_from_parent(a) < reach_from_parent(b); }));
    }
  }

  // Children of `j` by how far they reach, farthest first.
  std::vector<int> by_reach(int j) const {
    std::vector<int> out = limbs[static_cast<std::size_t>(j)];
    std::stable_sort(out.begin(), out.end(), [&](int a, int b) { return reach_from_parent(a) > reach_from_parent(b); });
    return out;
  }
};

// Along `chain`: the path length from its first joint to each.
std::vector<double> path_lengths(const Shape& shape, const std::vector<int>& chain) {
  std::vector<double> s(chain.size(), 0.0);
  for (std::size_t k = 1; k < chain.size(); ++k) s[k] = s[k - 1] + (shape.p(chain[k]) - shape.p(chain[k - 1])).norm();
  return s;
}

// The limb's end (hand, foot): the first joint after its root whose joints below reach less than
// half as far as it is from the root. Index into `chain`, or chain.size().
std::size_t limb_end(const Shape& shape, const std::vector<int>& chain, std::size_t root) {
  for (std::size_t k = root + 1; k < chain.size(); ++k)
    if (shape.reach(chain[k]) < 0.5 * (shape.p(chain[k]) - shape.p(chain[root])).norm()) return k;
  return chain.size();
}

// The joint a limb bends at (elbow, knee): of those between its root and its end, the nearest the
// middle of the path (joints twisting the bone lie nearer either end); the first of equals.
std::size_t limb_bend(const Shape& shape, const std::vector<int>& chain, std::size_t root, std::size_t end) {
  const std::vector<double> s = path_lengths(shape, chain);
  const double middle = 0.5 * (s[root] + s[end]);
  std::size_t best = chain.size();
  for (std::size_t k = root + 1; k < end; ++k)
    if (best == chain.size() || std::abs(s[k] - middle) < std::abs(s[best] - middle)) best = k;
  return best;
}

// The limb on `chain` given its root's index; empty `why` when found.
Limb limb_on(const Shape& shape, const std::vector<int>& chain, std::size_t root, bool leg, std::string& why) {
  const char* what = leg ? "leg" : "arm";
  Limb limb;
  limb.root = chain[root];
  if (root > 0) limb.girdle = chain[0];
  const std::size_t end = limb_end(shape, chain, root);
  if (end == chain.size()) {
    why = std::string("the ") + what + " from joint '" + shape.skeleton.joints[static_cast<std::size_t>(chain[0])].name + "' has no " + (leg ? "foot" : "hand");
    return limb;
  }
  const std::size_t bend = limb_bend(shape, chain, root, end);
  if (bend == chain.size()) {
    why = std::string("the ") + what + " from joint '" + shape.skeleton.joints[static_cast<std::size_t>(chain[0])].name + "' has no " + (leg ? "knee" : "elbow");
    return limb;
  }
  limb.bend = chain[bend];
  limb.end = chain[end];
  if (leg && end + 1 < chain.size()) limb.tip = chain[end + 1];
  return limb;
}

// Where two legs and the spine part (hips) and, above, two arms and the neck (chest): of the
// pairs of joints with three limbs each, the one whose four limbs' shortest reaches farthest.
struct Trunk {
  int hips = -1, chest = -1;
  std::array<int, 2> legs{-1, -1}, arms{-1, -1};
  int neck = -1;  // the first joint of the chest's third limb
};

Trunk find_trunk(const Shape& shape) {
  const std::size_t n = shape.skeleton.joints.size();
  std::vector<std::vector<int>> ranked(n);
  for (std::size_t j = 0; j < n; ++j)
    if (shape.limbs[j].size() >= 3) ranked[j] = shape.by_reach(static_cast<int>(j));
  Trunk best;
  double best_score = -1;
  for (std::size_t c = 0; c < n; ++c) {
    if (ranked[c].empty()) continue;
    const std::vector<int>& up = ranked[c];
    // Every hips above this chest: the ancestor with three limbs, the limb towards the chest left out.
    for (int below = static_cast<int>(c), h = shape.parent(below); h >= 0; below = h, h = shape.parent(h)) {
      if (ranked[static_cast<std::size_t>(h)].empty()) continue;
      std::vector<int> down;
      for (int limb : ranked[static_cast<std::size_t>(h)])
        if (limb != below && down.size() < 2) down.push_back(limb);
      const double score = std::min({shape.reach_from_parent(down[0]), shape.reach_from_parent(down[1]), shape.reach_from_parent(up[0]),
                                     shape.reach_from_parent(up[1])});
      if (score > best_score) {
        best_score = score;
        best.hips = h;
        best.chest = static_cast<int>(c);
        best.legs = {down[0], down[1]};
        best.arms = {up[0], up[1]};
        best.neck = up[2];
      }
    }
  }
  return best;
}

// Parts of the joints off the figure's chains: below a hand a finger's, below another limb's or
// the head's joint that joint's part, off the trunk (a prop on the spine) none.
void inherit_parts(const Skeleton& skeleton, std::vector<BodyPart>& parts, const std::vector<char>& marked) {
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (marked[j] || parent < 0) continue;
    const BodyPart above = parts[static_cast<std::size_t>(parent)];
    parts[j] = above == BodyPart::Hand ? BodyPart::Finger : above == BodyPart::Hips || above == BodyPart::Spine ? BodyPart::Other : above;
  }
}

// The head on the neck's chain: the joint its last bone (one a tenth as long as the chain's
// longest at least, counting the end site) starts from.
int head_on(const Shape& shape, const std::vector<int>& chain) {
  std::vector<Vec3> points;
  for (int j : chain) points.push_back(shape.p(j));
  double tip = 0;  // the end site below the last joint reaching farthest
  Vec3 end = points.back();
  for (std::size_t j = 0; j < shape.skeleton.joints.size(); ++j) {
    const Joint& joint = shape.skeleton.joints[j];
    if (joint.end_site && joint.parent == chain.back() && joint.offset.norm() > tip) tip = joint.offset.norm(), end = shape.at[j];
  }
  points.push_back(end);
  double longest = 0;
  for (std::size_t k = 1; k < points.size(); ++k) longest = std::max(longest, (points[k] - points[k - 1]).norm());
  for (std::size_t k = points.size() - 1; k > 0; --k)
    if ((points[k] - points[k - 1]).norm() >= 0.1 * longest) return chain[k - 1];
  return chain.front();
}

// The landmark joint of `h` a folded landmark name means; null for another name.
template <class H>
auto* landmark_slot(H& h, const std::string& folded) {
  static const char* const kTrunk[] = {"hips", "spine", "chest", "neck", "head"};
  decltype(&h.hips) trunk[] = {&h.hips, &h.spine, &h.chest, &h.neck, &h.head};
  for (std::size_t k = 0; k < 5; ++k)
    if (folded == kTrunk[k]) return trunk[k];
  for (std::size_t side = 0; side < 2; ++side) {
    const std::string prefix = side == 0 ? "left" : "right";
    if (folded.rfind(prefix, 0) != 0) continue;
    const std::string part = folded.substr(prefix.size());
    auto& arm = h.arms[side];
    auto& leg = h.legs[side];
    const std::pair<const char*, decltype(&h.hips)> limbs[] = {{"shoulder", &arm.girdle}, {"arm", &arm.root}, {"forearm", &arm.bend},
                                                               {"hand", &arm.end},       {"upleg", &leg.root}, {"leg", &leg.bend},
                                                               {"foot", &leg.end},       {"toe", &leg.tip}};
    for (const auto& [name, slot] : limbs)
      if (part == name) return slot;
  }
  return static_cast<decltype(&h.hips)>(nullptr);
}

// A pair of limbs as found: each one's main chain and joints, in the order the tree lists them.
struct LimbPair {
  std::array<std::vector<int>, 2> chains;
  std::array<Limb, 2> limbs;
};

// The legs from the hips: the thigh is the first joint away from the hips (CMU puts a hip joint
// before it), and each must go down, away from the chest. Empty `why` when found.
LimbPair legs_of(const Shape& shape, const Trunk& trunk, const Vec3& up, std::string& why) {
  LimbPair legs;
  const Vec3& hips = shape.p(trunk.hips);
  for (std::size_t k = 0; k < 2 && why.empty(); ++k) {
    const std::vector<int>& c = legs.chains[k] = shape.chain(trunk.legs[k]);
    const double length = path_lengths(shape, c).back() + (shape.p(c.front()) - hips).norm() + shape.reach(c.back());
    std::size_t root = 0;
    while (root + 1 < c.size() && (shape.p(c[root]) - hips).norm() <= 0.05 * length) ++root;
    legs.limbs[k] = limb_on(shape, c, root, true, why);
    if (why.empty() && (shape.p(legs.limbs[k].end) - hips).dot(up) >= 0)
      why = "the legs from joint '" + shape.skeleton.joints[static_cast<std::size_t>(trunk.hips)].name + "' do not go down, away from the arms";
  }
  return legs;
}

// The figure's left: it faces where its feet point (BVH's +z if it has no toes, then Blender's -y
// for a figure standing along z).
Vec3 left_of(const Shape& shape, const LimbPair& legs, const Vec3& up, double height) {
  Vec3 forward = Vec3::Zero();
  for (const Limb& leg : legs.limbs)
    if (leg.tip >= 0) forward += shape.p(leg.tip) - shape.p(leg.end);
  forward -= forward.dot(up) * up;
  for (const Vec3& facing : {Vec3(Vec3::UnitZ()), Vec3(-Vec3::UnitY())})
    if (forward.squaredNorm() < 1e-12 * height * height) forward = facing - facing.dot(up) * up;
  return up.cross(forward).normalized();
}

// The arms from the chest: the upper arm is the first joint as far to the side (from `mid`, along
// `left`) as the thighs (`hip_half`); a clavicle starts nearer the middle.
LimbPair arms_of(const Shape& shape, const Trunk& trunk, const Vec3& mid, const Vec3& left, double hip_half, std::string& why) {
  LimbPair arms;
  for (std::size_t k = 0; k < 2 && why.empty(); ++k) {
    const std::vector<int>& c = arms.chains[k] = shape.chain(trunk.arms[k]);
    std::size_t root = 0;
    while (root + 1 < c.size() && std::abs((shape.p(c[root]) - mid).dot(left)) < hip_half) ++root;
    arms.limbs[k] = limb_on(shape, c, root, false, why);
  }
  return arms;
}

// Every joint's part of the body: above the hips and the hips, the spine to the chest, the neck
// and head, the limbs joint by joint; those off these chains as inherit_parts says.
void assign_parts(const Shape& shape, Humanoid& h, const std::vector<int>& spine, const std::vector<int>& neck_chain, const LimbPair& legs,
                  const LimbPair& arms) {
  const Skeleton& skeleton = shape.skeleton;
  h.parts.assign(skeleton.joints.size(), BodyPart::Other);
  std::vector<char> marked(skeleton.joints.size(), 0);
  auto set = [&](int j, BodyPart part) {
    h.parts[static_cast<std::size_t>(j)] = part;
    marked[static_cast<std::size_t>(j)] = 1;
  };
  for (int j = h.hips; j >= 0; j = shape.parent(j)) set(j, BodyPart::Hips);  // joints above move it all
  for (int j : spine) set(j, BodyPart::Spine);
  for (int j : neck_chain) set(j, descends_from(skeleton, j, h.head) ? BodyPart::Head : BodyPart::Neck);
  auto set_limb = [&](const std::vector<int>& chain, const Limb& limb, std::array<BodyPart, 4> parts) {
    BodyPart part = parts[0];
    for (int j : chain) {
      if (j == limb.root) part = parts[1];
      if (j == limb.bend) part = parts[2];
      if (j == limb.end) part = parts[3];
      if (j == limb.tip) part = BodyPart::Toe;
      if (part == BodyPart::Hand && j != limb.end) part = BodyPart::Finger;
      set(j, part);
    }
  };
  for (std::size_t k = 0; k < 2; ++k) {
    set_limb(legs.chains[k], legs.limbs[k], {BodyPart::HipJoint, BodyPart::Thigh, BodyPart::Shin, BodyPart::Foot});
    set_limb(arms.chains[k], arms.limbs[k], {BodyPart::Clavicle, BodyPart::UpperArm, BodyPart::ForeArm, BodyPart::Hand});
  }
  inherit_parts(skeleton, h.parts, marked);
}

}  // namespace

HumanoidRecognition recognise_humanoid(const Skeleton& skeleton) {
  if (skeleton.joints.empty()) return {std::nullopt, "it has no joints"};
  const Shape shape(skeleton);
  const Trunk trunk = find_trunk(shape);
  if (trunk.hips < 0)
    return {std::nullopt, "no joint where two legs and a spine part (the hips) below one where two arms and a neck part (the chest)"};
  const double height = (shape.p(trunk.chest) - shape.p(trunk.hips)).norm();
  if (!(height > 0)) return {std::nullopt, "its chest is where its hips are"};
  const Vec3 up = (shape.p(trunk.chest) - shape.p(trunk.hips)) / height;
  std::string why;
  const LimbPair legs = legs_of(shape, trunk, up, why);
  if (!why.empty()) return {std::nullopt, why};
  const Vec3 left = left_of(shape, legs, up, height);
  auto side = [&](const Vec3& p, const Vec3& mid) { return (p - mid).dot(left); };
  const Vec3 mid = 0.5 * (shape.p(legs.limbs[0].root) + shape.p(legs.limbs[1].root));
  const double hip_half = 0.5 * std::abs(side(shape.p(legs.limbs[0].root), shape.p(legs.limbs[1].root)));
  const LimbPair arms = arms_of(shape, trunk, mid, left, hip_half, why);
  if (!why.empty()) return {std::nullopt, why};
  for (const LimbPair* pair : {&legs, &arms})
    if (side(shape.p(pair->limbs[0].root), mid) * side(shape.p(pair->limbs[1].root), mid) >= 0)
      return {std::nullopt, "its limbs are not one on each side of the figure"};

  Humanoid h;
  h.hips = trunk.hips;
  h.chest = trunk.chest;
  auto left_first = [&](const LimbPair& pair) {
    return side(shape.p(pair.limbs[0].root), mid) > 0 ? pair.limbs : std::array<Limb, 2>{pair.limbs[1], pair.limbs[0]};
  };
  h.legs = left_first(legs);
  h.arms = left_first(arms);
  // The spine: the joints from the hips up to the chest; the neck and head on the chest's third limb.
  std::vector<int> spine;
  for (int j = trunk.chest; j != trunk.hips; j = shape.parent(j)) spine.push_back(j);
  std::reverse(spine.begin(), spine.end());
  h.spine = spine.front();
  const std::vector<int> neck_chain = shape.chain(trunk.neck);
  h.head = head_on(shape, neck_chain);
  if (neck_chain.front() != h.head) h.neck = neck_chain.front();
  assign_parts(shape, h, spine, neck_chain, legs, arms);
  // A scene's joint_names decide over the shape.
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    if (skeleton.joints[j].named_by_scene)
      if (int* slot = landmark_slot(h, folded_joint_name(skeleton.joints[j].name))) *slot = static_cast<int>(j);
  return {std::move(h), ""};
}

const std::vector<std::string>& landmark_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out{"Hips", "Spine", "Chest", "Neck", "Head"};
    for (const char* side : {"Left", "Right"})
      for (const char* part : {"Shoulder", "Arm", "ForeArm", "Hand", "UpLeg", "Leg", "Foot", "Toe"}) out.push_back(std::string(side) + part);
    return out;
  }();
  return names;
}

std::optional<int> landmark_joint(const Humanoid& humanoid, const std::string& name) {
  const int* slot = landmark_slot(humanoid, folded_joint_name(name));
  if (!slot) return std::nullopt;
  return *slot;
}

std::vector<int> figure_order(const Skeleton& skeleton, const Humanoid& humanoid) {
  const Shape shape(skeleton);
  auto first = [](const Limb& limb) { return limb.girdle >= 0 ? limb.girdle : limb.root; };
  const std::vector<char> left = joints_below(skeleton, {first(humanoid.arms[0]), first(humanoid.legs[0])});
  const std::vector<char> right = joints_below(skeleton, {first(humanoid.arms[1]), first(humanoid.legs[1])});
  auto side = [&](int j) { return left[static_cast<std::size_t>(j)] ? 1 : right[static_cast<std::size_t>(j)] ? 2 : 0; };
  std::vector<int> order, stack{0};
  while (!stack.empty()) {
    const int j = stack.back();
    stack.pop_back();
    order.push_back(j);
    std::vector<int> next = shape.children[static_cast<std::size_t>(j)];
    std::stable_sort(next.begin(), next.end(), [&](int a, int b) {
      if (side(a) != side(b)) return side(a) < side(b);
      return shape.reach_from_parent(a) > shape.reach_from_parent(b);
    });
    stack.insert(stack.end(), next.rbegin(), next.rend());
  }
  return order;
}

std::vector<int> mirror_partners(const Skeleton& skeleton, const Humanoid& humanoid) {
  const Shape shape(skeleton);
  // Children in an order a mirror image keeps: farther reaching first, then by their offset's
  // height, depth and distance from the middle.
  auto ordered = [&](int j) {
    std::vector<int> out = shape.children[static_cast<std::size_t>(j)];
    auto key = [&](int c) {
      const Vec3& o = skeleton.joints[static_cast<std::size_t>(c)].offset;
      return std::tuple(-shape.reach_from_parent(c), o.y(), o.z(), std::abs(o.x()));
    };
    std::stable_sort(out.begin(), out.end(), [&](int a, int b) { return key(a) < key(b); });
    return out;
  };
  std::vector<int> partner(skeleton.joints.size());
  for (std::size_t j = 0; j < partner.size(); ++j) partner[j] = static_cast<int>(j);
  std::vector<std::pair<int, int>> pairs;
  auto first = [](const Limb& limb) { return limb.girdle >= 0 ? limb.girdle : limb.root; };
  for (const auto* limbs : {&humanoid.arms, &humanoid.legs}) pairs.emplace_back(first((*limbs)[0]), first((*limbs)[1]));
  while (!pairs.empty()) {
    const auto [a, b] = pairs.back();
    pairs.pop_back();
    partner[static_cast<std::size_t>(a)] = b;
    partner[static_cast<std::size_t>(b)] = a;
    const std::vector<int> left = ordered(a), right = ordered(b);
    if (left.size() != right.size())
      throw std::invalid_argument("joints '" + skeleton.joints[static_cast<std::size_t>(a)].name + "' and '" +
                                  skeleton.joints[static_cast<std::size_t>(b)].name + "', one the other's mirror image, have " +
                                  std::to_string(left.size()) + " and " + std::to_string(right.size()) + " joints below them");
    for (std::size_t k = 0; k < left.size(); ++k) pairs.emplace_back(left[k], right[k]);
  }
  return partner;
}

Humanoid humanoid_of(const Skeleton& skeleton) {
  HumanoidRecognition r = recognise_humanoid(skeleton);
  if (!r.humanoid) throw std::invalid_argument("its skeleton is not a humanoid's: " + r.why_not);
  return std::move(*r.humanoid);
}

}  // namespace vdc
