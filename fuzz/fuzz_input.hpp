// What the fuzz targets share: a scratch directory of this process where the input is written as
// a file, beside copies of the corpus's common files (tests/corpus/common), which a fuzzed scene
// may name as "sheet.obj" or "../common/sheet.obj".
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace vdc::fuzz {

// Writes the input to the scratch directory under `name` and returns its path. The directory is
// made on the first call (libFuzzer's entry point keeps no state of its own) and removed at exit.
std::string write_input(const uint8_t* data, std::size_t size, const std::string& name);

}  // namespace vdc::fuzz
