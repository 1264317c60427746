// Crowds (a scene's "crowds", docs/scene-format.md): K copies of a template character and the
// garments it wears, placed on a grid, on a circle or at seeded random positions, each with its
// own start offset, speed and motion, each copy its own garment group. A crowd becomes garment
// and obstacle entries before the scene reads them; each entry keeps its template's place in
// the file, so an error names the template and the copy.
#pragma once
#include <string>
#include <vector>

#include "core/math.hpp"
#include "io/json_reader.hpp"

namespace vdc {

// One copy of a crowd's template.
struct CrowdCopy {
  std::string group;   // the copy's garment group and its character's name: the crowd's name and number
  Vec3 position;       // where the figure's origin stands
  double heading = 0;  // degrees about +y (0: the figure faces +z, as authored)
  double start = 0;    // s, added to the template character's clip start
  double speed = 1;    // times the template character's speed
  std::string motion;  // the motion file as written (relative to the scene), empty: the template's
  bool mirror = false; // the motion mirrored left for right (the character's "mirror")
};

// The copies of one crowd block, in order, every random draw from its seed.
std::vector<CrowdCopy> place_crowd(const JsonValue& crowd);

// A scene's garment and obstacle entries: those it lists, then its crowds' copies.
struct SceneEntries {
  std::vector<JsonValue> garments, obstacles;
};
SceneEntries scene_entries(const JsonValue& scene);

}  // namespace vdc
