// The shot camera exported frame by frame (camera.json, camera.chan).
#include "output/camera_export.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/text_file.hpp"

namespace vdc {

namespace {

constexpr double kDegrees = 180.0 / M_PI;
// The channel file's coordinates to a tenth of a nanometre and angles to 1e-10 degrees: read back
// (a scene's "camera": {"chan": ...}), it gives the same view within 1e-9.
constexpr int kDecimals = 10;

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::vector<CameraFrame> camera_frames(const CameraPath& path, double frame_time, int frames) {
  std::vector<CameraFrame> out;
  const double before = -std::numeric_limits<double>::infinity();
  for (int f = 0; f <= frames; ++f) {
    CameraFrame c;
    c.frame = f;
    c.time = f * frame_time;
    c.camera = path.at(c.time);
    c.shot = static_cast<int>(path.cuts_in(before, c.time).size());
    c.cut = f > 0 && !path.cuts_in((f - 1) * frame_time, c.time).empty();
    c.rotation_degrees = zxy_euler_degrees(c.camera);
    out.push_back(c);
  }
  return out;
}

std::string camera_file(const std::string& dir, const std::string& name, const std::string& extension) {
  return dir + (name.empty() ? "/camera" : "/camera_" + name) + extension;
}

void write_camera_files(const CameraPath& path, double frame_time, int frames, const std::string& dir, const std::string& name, int index) {
  const std::vector<CameraFrame> shot = camera_frames(path, frame_time, frames);
  const Camera& lens = path.lens();
  const double fov_x = 2 * std::atan(std::tan(0.5 * lens.fov_y_degrees / kDegrees) * lens.width / lens.height) * kDegrees;

  nlohmann::json j;
  if (!name.empty()) j["name"] = name, j["index"] = index;  // the scene's order of its cameras
  if (lens.eye_offset != 0) j["eye_offset"] = lens.eye_offset;  // a stereo eye: m along the camera's right
  j["units"] = "m";
  j["up_axis"] = "y";
  j["frame_time"] = frame_time;
  j["width"] = lens.width;
  j["height"] = lens.height;
  j["fov_y_degrees"] = lens.fov_y_degrees;
  j["fov_x_degrees"] = fov_x;
  j["near"] = lens.near;
  j["far"] = lens.far;
  j["sensor_height_mm"] = lens.sensor_height_mm;
  j["focal_length_mm"] = lens.focal_length_mm();
  // The focus distance is each frame's (it follows the target with focus_on_target); here the
  // first frame's, for tools that take one.
  const bool depth_of_field = lens.focus_on_target || lens.focus_distance > 0;
  if (depth_of_field)
    j["depth_of_field"] = {{"focus_distance", shot.empty() ? lens.focus_distance : shot.front().camera.focus_distance},
                           {"f_stop", lens.f_stop},
                           {"follows_target", lens.focus_on_target}};
  if (lens.shutter > 0) j["shutter"] = lens.shutter;
  j["rotation_order"] = "ZXY";
  j["frames"] = nlohmann::json::array();
  for (const CameraFrame& c : shot) {
    const auto [right, up, forward] = c.camera.basis();
    j["frames"].push_back({{"frame", c.frame},
                           {"time", c.time},
                           {"shot", c.shot},
                           {"cut", c.cut},
                           {"position", vec(c.camera.position)},
                           {"target", vec(c.camera.target)},
                           {"forward", vec(forward)},
                           {"up", vec(up)},
                           {"rotation_degrees", vec(c.rotation_degrees)}});
    if (depth_of_field) j["frames"].back()["focus_distance"] = c.camera.focus_distance;
    if (c.camera.fov_y_degrees != lens.fov_y_degrees) j["frames"].back()["fov_y_degrees"] = c.camera.fov_y_degrees;  // a zoom
  }
  const std::string json_path = camera_file(dir, name, ".json");
  std::ofstream json_file(json_path);
  json_file << j.dump(1) << "\n";
  if (!json_file.flush()) throw OutputError(json_path, "cannot write");

  const std::string chan_path = camera_file(dir, name, ".chan");
  TextFile chan(chan_path);
  for (const CameraFrame& c : shot) {
    chan.integer(c.frame);
    for (int k = 0; k < 3; ++k) chan.text(" ").fixed(c.camera.position[k], kDecimals);
    for (int k = 0; k < 3; ++k) chan.text(" ").fixed(c.rotation_degrees[k], kDecimals);
    chan.text(" ").fixed(c.camera.fov_y_degrees, kDecimals).text("\n");
  }
  if (!chan.close()) throw OutputError(chan_path, "cannot write");
}

std::vector<std::string> camera_files_in(const std::string& dir, const std::string& extension) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string file = e.path().filename().string();
    if ((file == "camera" + extension || file.rfind("camera_", 0) == 0) && e.path().extension() == extension) files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void remove_camera_files(const std::string& dir) {
  std::error_code ec;
  for (const char* extension : {".json", ".chan"})
    for (const std::string& file : camera_files_in(dir, extension))
      if (std::filesystem::remove(file, ec); ec) throw OutputError(file, "cannot remove this file of an earlier run");
}

}  // namespace vdc
