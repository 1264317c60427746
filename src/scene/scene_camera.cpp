// The `camera` block and the `cameras` list (docs/scene-format.md, "camera" and "cameras"): each
// camera's lens and keyframed path with its cuts, or its path read from a channel file; a stereo
// camera as its two eyes.
#include "scene/scene_blocks.hpp"

#include <set>
#include <string>

#include "io/chan.hpp"
#include "scene/model_camera.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

// The keys of a camera read back from a channel file (`chan`, camera.chan or Nuke's and Maya's):
// chan frame `first_frame` (default 0) at scene time 0, one key a frame `frame_time` apart, the
// pose from the translation and ZXY rotation (the up vector the roll's), the target 1 m ahead,
// the field of view the line's or the lens's.
std::vector<CameraKey> chan_keys(const JsonValue& j, const std::string& scene_path, double frame_time) {
  if (j.has("keys") || j.has("up")) j.fail("a camera from a channel file takes its keys and up vector from it: leave out \"keys\" and \"up\"");
  const JsonValue file = j.at("chan");
  const std::string path = resolve_file(file, scene_path);
  const std::vector<ChanFrame> frames = with_key(file, [&] { return read_chan(path); });
  const double first = j.number_or("first_frame", 0.0);
  std::vector<CameraKey> keys;
  for (const ChanFrame& f : frames) {
    const Mat3 r = zxy_rotation(f.rotation_degrees);  // columns: right, up, back
    CameraKey key;
    key.time = (f.frame - first) * frame_time;
    key.position = f.translation;
    key.target = f.translation - r.col(2);
    key.up = r.col(1);
    key.fov_y_degrees = f.fov_y_degrees;
    keys.push_back(key);
  }
  return keys;
}

// A camera from an animation package's file (`file`): the file's camera `in_file`, moving as a
// clip (`clip`) moves its node, with the file's field of view and clip planes unless the block
// gives `near` and `far`.
CameraPath file_camera_path(const JsonValue& j, const std::string& in_file, const std::string& scene_path, const Camera& lens) {
  for (const char* key : {"keys", "up", "fov", "chan"})
    if (j.has(key)) j.at(key).fail("a camera from a file takes its path, up vector and field of view from it: leave this out");
  const JsonValue file = j.at("file");
  const std::string path = resolve_file(file, scene_path);
  ClipChoice clip;
  if (auto k = j.find("clip")) clip = k->is_string() ? ClipChoice(k->string()) : ClipChoice(k->integer());
  FileCamera camera = with_key(j.has("clip") ? j.at("clip") : file, [&] { return read_file_camera(path, in_file, clip, lens); });
  if (j.has("near")) camera.lens.near = lens.near;
  if (j.has("far")) camera.lens.far = lens.far;
  if (camera.lens.far <= camera.lens.near) file.fail("the camera's far plane must lie beyond its near plane (give \"near\" and \"far\")");
  return CameraPath(camera.lens, std::move(camera.keys));
}

// The lens and path of one camera entry (`name` and `stereo` read by the caller); `in_file`
// names a camera of its `file`.
CameraPath parse_camera_path(const JsonValue& j, const std::string& scene_path, double frame_time, const std::string& in_file) {
  Camera lens;
  lens.fov_y_degrees = j.positive_or("fov", lens.fov_y_degrees);
  if (lens.fov_y_degrees >= 180) j.at("fov").fail("must be below 180 degrees");
  const long long w = j.integer_or("width", lens.width), h = j.integer_or("height", lens.height);
  if (w < 1 || w > 100000) j.at("width").fail("must be between 1 and 100000 pixels");
  if (h < 1 || h > 100000) j.at("height").fail("must be between 1 and 100000 pixels");
  lens.width = static_cast<int>(w);
  lens.height = static_cast<int>(h);
  lens.near = j.positive_or("near", lens.near);
  lens.far = j.positive_or("far", lens.far);
  if (lens.far <= lens.near) j.at("far").fail("must be beyond near");
  lens.up = j.vec3_or("up", lens.up);
  if (lens.up.norm() == 0) j.at("up").fail("must not be zero");
  const auto focus = j.find("focus_distance");
  lens.focus_on_target = focus && focus->is_string();
  if (lens.focus_on_target && j.has("chan")) focus->fail("a camera from a channel file has no target to focus on: give a distance in metres");
  if (lens.focus_on_target && focus->string() != "target")
    focus->fail("expected a distance in metres, or \"target\" for the focus to follow the camera's target");
  if (!lens.focus_on_target) lens.focus_distance = j.non_negative_or("focus_distance", lens.focus_distance);
  lens.f_stop = j.positive_or("f_stop", lens.f_stop);
  if (lens.f_stop < 0.5 || lens.f_stop > 256) j.at("f_stop").fail("must be between 0.5 and 256");
  lens.sensor_height_mm = j.positive_or("sensor_height", lens.sensor_height_mm);
  if (lens.sensor_height_mm > 1000) j.at("sensor_height").fail("must be at most 1000 (millimetres)");
  if (lens.focus_distance > 0 && lens.focus_distance <= 1e-3 * lens.focal_length_mm())
    j.at("focus_distance").fail("must be beyond the focal length (" + std::to_string(lens.focal_length_mm()) + " mm), or 0 for no depth of field");
  lens.shutter = j.non_negative_or("shutter", lens.shutter);
  if (lens.shutter > 1) j.at("shutter").fail("must be at most 1 (the whole frame time)");
  if (j.has("chan")) return CameraPath(lens, chan_keys(j, scene_path, frame_time));
  if (j.has("file")) return file_camera_path(j, in_file, scene_path, lens);
  std::vector<CameraKey> keys;
  const JsonValue list = j.at("keys");
  for (const JsonValue& k : list.items()) {
    k.only_keys({"time", "position", "target", "cut"});
    CameraKey key;
    key.time = k.at("time").non_negative();
    key.position = k.at("position").vec3();
    key.target = k.at("target").vec3();
    if (auto cut = k.find("cut")) key.cut = cut->boolean();
    if (!keys.empty() && !(key.time > keys.back().time)) k.at("time").fail("keyframe times must increase");
    if ((key.target - key.position).norm() == 0) k.at("target").fail("must differ from the position");
    if (((key.target - key.position).normalized().cross(lens.up.normalized())).norm() < 1e-6)
      k.at("target").fail("the view direction is parallel to the camera's up vector");
    keys.push_back(key);
  }
  if (keys.empty()) list.fail("a camera needs at least one key");
  return CameraPath(lens, std::move(keys));
}

// The camera `j` describes, named `name`: itself, or with `stereo` its left and right eyes, the
// camera moved half the interaxial distance to either side (`name`_left and `name`_right, or left
// and right for the unnamed `camera`). `in_file`: the name of its camera in its `file`
// (`file_camera` overrides it).
void add_camera(const JsonValue& j, const std::string& name, const std::string& scene_path, double frame_time, std::vector<ShotCamera>& cameras,
                const std::string& in_file) {
  const CameraPath path = parse_camera_path(j, scene_path, frame_time, j.string_or("file_camera", in_file));
  const auto stereo = j.find("stereo");
  if (!stereo) {
    cameras.push_back({name, path});
    return;
  }
  stereo->only_keys({"interaxial"});
  const double interaxial = stereo->at("interaxial").positive();
  if (interaxial > 10) stereo->at("interaxial").fail("must be at most 10 m (the distance between the two eyes)");
  const std::string prefix = name.empty() ? "" : name + "_";
  for (const auto& [eye, side] : {std::pair{"left", -0.5}, std::pair{"right", 0.5}}) {
    Camera lens = path.lens();
    lens.eye_offset = side * interaxial;
    cameras.push_back({prefix + eye, CameraPath(lens, path.keys())});
  }
}

}  // namespace

std::vector<ShotCamera> parse_cameras(const JsonValue& top, const std::string& scene_path, double frame_time) {
  std::vector<ShotCamera> cameras;
  const auto one = top.find("camera"), many = top.find("cameras");
  if (one && many) many->fail("a scene has either one \"camera\" or a list of \"cameras\", not both");
  if (one) {
    one->only_keys({"fov", "width", "height", "near", "far", "up", "keys", "focus_distance", "f_stop", "sensor_height", "shutter", "stereo",
                    "chan", "first_frame", "file", "name", "file_camera", "clip"});
    if (one->has("name") && !one->has("file")) one->at("name").fail("the one camera has no name: name cameras in a \"cameras\" list");
    // The one camera's `name` is its camera's in the file (the run's files stay camera.json).
    add_camera(*one, "", scene_path, frame_time, cameras, one->string_or("name", ""));
  }
  if (!many) return cameras;
  const std::vector<JsonValue> entries = many->items();
  if (entries.empty()) many->fail("lists no camera: give at least one, or leave \"cameras\" out");
  std::set<std::string> names;
  for (const JsonValue& c : entries) {
    c.only_keys({"name", "fov", "width", "height", "near", "far", "up", "keys", "focus_distance", "f_stop", "sensor_height", "shutter", "stereo",
                 "chan", "first_frame", "file", "file_camera", "clip"});
    const std::string name = c.at("name").string();
    check_name(c.at("name"), name, names);
    const std::size_t first = cameras.size();
    add_camera(c, name, scene_path, frame_time, cameras, name);
    for (std::size_t k = first; k < cameras.size(); ++k)  // a stereo camera's eyes are names too
      if (cameras[k].name != name) check_name(c.at("name"), cameras[k].name, names);
  }
  return cameras;
}

}  // namespace vdc
