#include "physics/material.hpp"

#include <cmath>

namespace vdc {

MembraneStiffness Material::membrane() const {
  return {warp, poisson * std::sqrt(warp * weft), weft, shear};
}

}  // namespace vdc
