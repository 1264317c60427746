// A camera from an animation package's file (model_file.hpp): the camera node's pose at every
// sample of a clip (position, view and up vector, so the roll comes along), its field of view and
// clip planes, in metres with y up.
#pragma once
#include <string>
#include <vector>

#include "scene/model_file.hpp"
#include "view/camera.hpp"

namespace vdc {

struct FileCamera {
  Camera lens;  // the given lens with the file's field of view and clip planes
  std::vector<CameraKey> keys;  // one a clip sample (one alone for a still camera), each with its up
  std::vector<std::string> names;  // every camera's name in the file
};

// The file's camera `name` (empty: its only camera). The clip is `clip` if one is asked for,
// else the first that moves the camera's node or a node above it (none: the camera stands
// still); its first key is time 0. The vertical field of view comes from the file's horizontal
// one and aspect ratio (`lens`'s image when the file gives none); the target lies 1 m along
// the view. Throws InputError for a file without that camera (naming the ones it has).
FileCamera read_file_camera(const std::string& path, const std::string& name, const ClipChoice& clip, const Camera& lens);

}  // namespace vdc
