// Every crossing in one part of a run, by the exact triangle tests: each garment against its
// bodies, the other garments and itself.
#pragma once
#include <string>

#include "scene/scene.hpp"
#include "support/triangle_soup.hpp"

namespace vdc::test {

// A description of the first crossing, or "" when there is none.
inline std::string first_crossing(const Scene& part) {
  for (std::size_t i = 0; i < part.garments.size(); ++i) {
    const GarmentSpec& g = part.garments[i];
    if (const int n = self_crossings(g.mesh)) return g.name + " crosses itself (" + std::to_string(n) + " face pairs)";
    for (const ObstacleSpec& o : part.obstacles)
      if (const int n = crossings_between(g.mesh, o.mesh)) return g.name + " crosses " + o.name + " (" + std::to_string(n) + " face pairs)";
    for (std::size_t j = i + 1; j < part.garments.size(); ++j)
      if (const int n = crossings_between(g.mesh, part.garments[j].mesh))
        return g.name + " crosses " + part.garments[j].name + " (" + std::to_string(n) + " face pairs)";
  }
  return "";
}

}  // namespace vdc::test
