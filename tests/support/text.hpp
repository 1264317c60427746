// Small text helpers shared by tests.
#pragma once
#include <string>

namespace vdc::test {

// Whether `part` occurs in `s` (for error messages that must name something).
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace vdc::test
