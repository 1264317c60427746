// libFuzzer target: an OBJ file read as a garment (pattern coordinates required) and as an
// obstacle (positions only), each built into a checked mesh. Bad input must end in InputError;
// any other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "io/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = vdc::fuzz::write_input(data, size, "input.obj");
  for (const bool garment : {true, false}) {
    try {
      vdc::read_obj(path, garment);
    } catch (const vdc::InputError&) {
    }
  }
  return 0;
}
