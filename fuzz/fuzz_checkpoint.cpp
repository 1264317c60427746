// libFuzzer target: a run's checkpoint read back (output/checkpoint.hpp). The input's last eight
// bytes are made its checksum first, so that mutations reach the reader past the checksum test.
// Bad input must end in InputError; any other exception, a crash or a sanitizer report is a
// finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/binary_io.hpp"
#include "core/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "output/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  if (size >= sizeof(uint64_t)) {
    const std::size_t body = size - sizeof(uint64_t);
    const uint64_t sum = vdc::fnv1a64(reinterpret_cast<const char*>(bytes.data()), body);
    std::memcpy(bytes.data() + body, &sum, sizeof sum);
  }
  try {
    vdc::read_checkpoint(vdc::fuzz::write_input(bytes.data(), bytes.size(), "checkpoint.bin"));
  } catch (const vdc::InputError&) {
  }
  return 0;
}
