// Reading a text input file whole, refusing what is not one: a directory or device, a file too
// large for its kind, bytes that are not text (a NUL byte).
#pragma once
#include <cstdint>
#include <string>

namespace vdc {

// The bytes of `path`, a regular file of at most `max_bytes` with no NUL byte. Throws InputError
// naming the file and the problem; `kind` names what it should be ("JSON", "OBJ", "BVH").
std::string read_input_text(const std::string& path, std::uintmax_t max_bytes, const std::string& kind);

}  // namespace vdc
