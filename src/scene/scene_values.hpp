// Values the scene file's blocks share: files named relative to the scene, keyframe tracks,
// transforms, names of output files, and the errors of a referenced file under its key.
#pragma once
#include <set>
#include <string>

#include "core/error.hpp"
#include "core/track.hpp"
#include "io/json_reader.hpp"
#include "scene/transform.hpp"

namespace vdc {

// The file a scene's string names (relative to the scene file unless absolute), which must be a
// regular file.
std::string resolve_file(const JsonValue& j, const std::string& scene_path);

// Runs a loader of a referenced file; its errors keep their own file and line and gain the key path.
template <class F>
auto with_key(const JsonValue& j, F&& load) {
  try {
    return load();
  } catch (const InputError& e) {
    throw InputError(j.file(), j.path(), e.what());
  }
}

// Keyframes [{"time": t, "<name>": [x, y, z]}, ...] with increasing times.
Vec3Track parse_track(const JsonValue& list, const char* name);

// {"scale": s, "rotate": [rx, ry, rz], "translate": [x, y, z]}.
Transform parse_transform(const JsonValue& j);

// A garment's or obstacle's name: a part of its output files' names, used once in the scene.
void check_name(const JsonValue& where, const std::string& name, std::set<std::string>& seen);

}  // namespace vdc
