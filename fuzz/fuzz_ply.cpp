// libFuzzer target: a view-factor PLY as `vdcloth render --colour view` reads it beside a frame.
// Bad input must end in InputError; any other exception, a crash, a sanitizer report or an index
// outside the vertices read is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "io/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = vdc::fuzz::write_input(data, size, "input.ply");
  try {
    const vdc::PlyFaceValues ply = vdc::read_ply_with_face_values(path);
    for (const auto& face : ply.faces)
      for (const int32_t v : face)
        if (v < 0 || static_cast<std::size_t>(v) >= ply.positions.size()) std::abort();
    if (ply.values.size() != ply.faces.size()) std::abort();
  } catch (const vdc::InputError&) {
  }
  return 0;
}
