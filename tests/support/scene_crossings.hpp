// Every crossing in one part of a scene or of a run, by the exact triangle tests: each garment
// against its bodies, the other garments and itself.
#pragma once
#include <string>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/triangle_soup.hpp"

namespace vdc::test {

// A description of the first crossing among named garment and obstacle meshes, or "" when
// there is none.
template <class Garment, class Obstacle>
std::string first_crossing(std::size_t garments, std::size_t obstacles, Garment&& garment, Obstacle&& obstacle) {
  for (std::size_t i = 0; i < garments; ++i) {
    const auto& [name, mesh] = garment(i);
    if (const int n = self_crossings(mesh)) return name + " crosses itself (" + std::to_string(n) + " face pairs)";
    for (std::size_t k = 0; k < obstacles; ++k) {
      const auto& [other, body] = obstacle(k);
      if (const int n = crossings_between(mesh, body)) return name + " crosses " + other + " (" + std::to_string(n) + " face pairs)";
    }
    for (std::size_t j = i + 1; j < garments; ++j) {
      const auto& [other, cloth] = garment(j);
      if (const int n = crossings_between(mesh, cloth)) return name + " crosses " + other + " (" + std::to_string(n) + " face pairs)";
    }
  }
  return "";
}

// In a scene as loaded.
inline std::string first_crossing(const Scene& part) {
  return first_crossing(
      part.garments.size(), part.obstacles.size(),
      [&](std::size_t i) { return std::pair<const std::string&, const Mesh&>(part.garments[i].name, part.garments[i].mesh); },
      [&](std::size_t k) { return std::pair<const std::string&, const Mesh&>(part.obstacles[k].name, part.obstacles[k].mesh); });
}

// In a run's part as it is now: its garments' meshes and its obstacles' at its time.
inline std::string first_crossing(const Simulation& part) {
  const Scene& s = part.scene();
  return first_crossing(
      s.garments.size(), s.obstacles.size(),
      [&](std::size_t i) { return std::pair<const std::string&, const Mesh&>(s.garments[i].name, part.garment_mesh(i)); },
      [&](std::size_t k) { return std::pair<const std::string&, const Mesh&>(s.obstacles[k].name, part.obstacle_mesh(k)); });
}

}  // namespace vdc::test
