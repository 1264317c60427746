// libFuzzer target: a rigged character's file read through libassimp as glTF, FBX, Collada and
// X (the importer also sniffs the content), then posed within and after its clip: every joint
// and every skinned vertex finite, and the skin's repaired surface one build_mesh accepts. Bad
// input must end in InputError; any other exception, a crash, a sanitizer report, a non-finite
// point or a refused surface is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "scene/body.hpp"
#include "scene/rigged_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  for (const char* name : {"input.gltf", "input.fbx", "input.dae", "input.x"}) {
    const std::string path = vdc::fuzz::write_input(data, size, name);
    vdc::RiggedModel model;
    try {
      model = vdc::read_rigged_model(path);
    } catch (const vdc::InputError&) {
      continue;
    }
    vdc::MeshSource surface = model.skin;
    vdc::with_canonical_uvs(surface);
    try {
      vdc::build_mesh(surface);
    } catch (const vdc::MeshBuildError&) {
      std::abort();
    }
    const vdc::Body body(model.motion, vdc::Skin{model.skin, model.weights});
    const double duration = model.motion.duration();
    for (const double t : {0.0, 0.5 * duration, duration + 1.0}) {
      const vdc::Pose pose = model.motion.pose_at(t);
      for (const auto& joint : model.motion.world(pose))
        if (!joint.matrix().allFinite()) std::abort();
      for (const vdc::Vec3& x : body.skin(pose))
        if (!x.allFinite()) std::abort();
    }
  }
  return 0;
}
