// The shot camera frame by frame, for other tools: DIR/camera.json (pose, lens, cuts) and
// DIR/camera.chan (the channel file Nuke, Houdini and Blender's Nuke add-on read: frame,
// translation, rotation in degrees, vertical field of view), both in the scene's metres, y up;
// a scene's named cameras (its `cameras` list) as DIR/camera_NAME.json and DIR/camera_NAME.chan.
#pragma once
#include <string>
#include <vector>

#include "view/camera.hpp"

namespace vdc {

struct CameraFrame {
  int frame = 0;
  double time = 0;  // s, frame * frame_time
  Camera camera;
  int shot = 0;      // 0 until the first cut, then one more at each cut
  bool cut = false;  // a cut in (the previous frame's time, this frame's time]
  Vec3 rotation_degrees = Vec3::Zero();  // zxy_euler_degrees(camera)
};

// Frames 0 to `frames` of the path, frame f at time f * frame_time.
std::vector<CameraFrame> camera_frames(const CameraPath& path, double frame_time, int frames);

// DIR/camera.json (extension ".json") of the unnamed camera, DIR/camera_NAME.json of camera NAME.
std::string camera_file(const std::string& dir, const std::string& name, const std::string& extension);
// Writes camera `name`'s (empty: the scene's one unnamed camera; else the scene's camera number
// `index`) JSON and channel files for frames 0 to `frames`. Throws OutputError naming the file
// that cannot be written.
void write_camera_files(const CameraPath& path, double frame_time, int frames, const std::string& dir, const std::string& name = "",
                        int index = 0);
// The camera files of a run directory with `extension` (".json" or ".chan"): camera.json, or
// camera_NAME.json for each named camera, in the order of their names.
std::vector<std::string> camera_files_in(const std::string& dir, const std::string& extension);
// Removes the camera files of an earlier run (camera.json, camera.chan, camera_*.json,
// camera_*.chan) if they are there.
void remove_camera_files(const std::string& dir);

}  // namespace vdc
