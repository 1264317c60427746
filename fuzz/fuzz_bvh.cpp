// libFuzzer target: a BVH motion parsed, then posed before, within and after its frames (forward
// kinematics of every joint), every joint's place finite; its skeleton recognised as a humanoid
// or not, and a humanoid's landmarks, figure order and mirror partners consistent. Bad input must
// end in InputError; any other exception, a crash, a sanitizer report, a non-finite joint or an
// inconsistent humanoid is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/humanoid.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  vdc::Motion motion;
  try {
    motion = vdc::parse_bvh(std::string(reinterpret_cast<const char*>(data), size), "input.bvh");
  } catch (const vdc::InputError&) {
    return 0;
  }
  const double duration = motion.duration();
  for (const double t : {-1.0, 0.0, 0.37 * duration, duration, duration + 1.0})
    for (const auto& joint : motion.world(motion.pose_at(t)))
      if (!joint.matrix().allFinite()) std::abort();
  const vdc::HumanoidRecognition figure = vdc::recognise_humanoid(motion.skeleton);
  if (!figure.humanoid) return 0;
  const int n = static_cast<int>(motion.skeleton.joints.size());
  for (const std::string& name : vdc::landmark_names()) {
    const std::optional<int> j = vdc::landmark_joint(*figure.humanoid, name);
    if (!j || *j < -1 || *j >= n) std::abort();
  }
  if (static_cast<int>(figure.humanoid->parts.size()) != n) std::abort();
  std::vector<int> order = vdc::figure_order(motion.skeleton, *figure.humanoid);
  std::sort(order.begin(), order.end());
  for (int j = 0; j < n; ++j)
    if (order[static_cast<std::size_t>(j)] != j) std::abort();  // every joint once
  try {
    const std::vector<int> partner = vdc::mirror_partners(motion.skeleton, *figure.humanoid);
    for (int j = 0; j < n; ++j)
      if (partner[static_cast<std::size_t>(partner[static_cast<std::size_t>(j)])] != j) std::abort();
    vdc::mirrored(motion);
  } catch (const std::invalid_argument&) {
    // limbs of different shapes, or partners of different channels: said, not a finding
  }
  return 0;
}
