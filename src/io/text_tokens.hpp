// Numbers in the text formats read line by line (OBJ, PLY): each refusal an InputError naming
// the file and the line.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace vdc {

// "line N", the place an InputError names.
std::string line_place(int line);

// A finite number, the whole token (a leading '+' allowed).
double parse_text_number(const std::string& token, const std::string& path, int line);

// A position or material coordinate: in metres, so nothing near the doubles' range (a vertex at
// 1e308 would make every area and normal overflow, and be reported as a zero-area face).
double parse_coordinate(const std::string& token, const std::string& path, int line);

// A count or index from 0 to `largest`, the whole token.
int64_t parse_whole_number(const std::string& token, int64_t largest, const std::string& what, const std::string& path, int line);

}  // namespace vdc
