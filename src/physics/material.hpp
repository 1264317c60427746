// Fabric material in physical units: area density (kg/m^2), stretch stiffness (N/m) along warp,
// weft and in shear, bending stiffness (N m). Read from files by scene/material_file.hpp.
#pragma once
#include <string>

#include "physics/membrane.hpp"

namespace vdc {

struct Material {
  std::string name;
  std::string source;    // where the values come from
  double density = 0.15;  // kg/m^2
  double warp = 4000;     // N/m, material u axis
  double weft = 3000;     // N/m, material v axis
  double shear = 300;     // N/m
  double poisson = 0.2;   // warp-weft coupling: c12 = poisson sqrt(warp weft)
  double bending = 1e-5;  // N m

  MembraneStiffness membrane() const;
};

}  // namespace vdc
