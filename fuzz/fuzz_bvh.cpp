// libFuzzer target: a BVH motion parsed, then posed before, within and after its frames (forward
// kinematics of every joint), every joint's place finite. Bad input must end in InputError; any
// other exception, a crash, a sanitizer report or a non-finite joint is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"

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
  return 0;
}
