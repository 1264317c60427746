// The camera `vdcloth render`, `fidelity` and `report` look through: the scene's first camera, or
// the one `--camera NAME` names (a scene with a `cameras` list, or a stereo camera's eyes).
#pragma once
#include <string>

#include "scene/scene.hpp"

namespace vdc {

// Keeps only the camera named `name` (the first for an empty name) in the scene. Throws
// InputError naming the scene file when it has no camera (`needed_for`: what the command wanted
// one for), UsageError listing the scene's cameras when none has that name.
void choose_camera(Scene& scene, const std::string& name, const std::string& needed_for);

}  // namespace vdc
