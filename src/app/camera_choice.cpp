// The camera a command looks through, by --camera.
#include "app/camera_choice.hpp"

#include "app/cli.hpp"
#include "core/error.hpp"

namespace vdc {

void choose_camera(Scene& scene, const std::string& name, const std::string& needed_for) {
  if (scene.cameras.empty()) throw InputError(scene.path, "camera", "the scene has no camera " + needed_for);
  const ShotCamera* chosen = scene.find_camera(name);
  if (chosen == nullptr) {
    std::string names;
    for (const ShotCamera& c : scene.cameras) names += (names.empty() ? "" : ", ") + (c.name.empty() ? "(unnamed)" : c.name);
    throw UsageError("--camera " + name + ": the scene " + scene.path + " has no camera of that name (its cameras: " + names + ")");
  }
  ShotCamera kept = *chosen;
  scene.cameras = {std::move(kept)};
}

}  // namespace vdc
