// Checks of a mesh that many tests make.
#pragma once
#include <gtest/gtest.h>

#include "core/mesh.hpp"

namespace vdc::test {

// The mesh passes its own validation (Mesh::validate), its report shown when it does not.
inline void expect_valid(const Mesh& m) {
  const ValidationReport r = m.validate();
  EXPECT_TRUE(r.ok()) << r.summary();
}

}  // namespace vdc::test
