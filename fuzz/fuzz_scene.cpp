// libFuzzer target: a scene file (docs/scene-format.md) read and checked with everything it names
// (materials, meshes, sequences, motions, skins, procedural garments and bodies). Bad input must
// end in InputError; any other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    vdc::load_scene(vdc::fuzz::write_input(data, size, "scene.json"));
  } catch (const vdc::InputError&) {
  }
  return 0;
}
