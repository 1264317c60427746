// libFuzzer target: an OBJ file read as a garment (pattern coordinates required) and as an
// obstacle (positions only), each built into a checked mesh, the obstacle's surface repaired
// for collisions first (a surface with no face of any area may be refused). Bad input must end
// in InputError; any other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "core/surface_repair.hpp"
#include "io/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = vdc::fuzz::write_input(data, size, "input.obj");
  try {
    vdc::read_obj(path, true);
  } catch (const vdc::InputError&) {
  }
  try {
    vdc::build_obstacle_mesh(vdc::read_obj_source(path, false));
  } catch (const vdc::InputError&) {
  } catch (const vdc::MeshBuildError&) {  // no face with an area, a position not finite
  }
  return 0;
}
