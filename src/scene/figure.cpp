// The project's figure skeleton and keyframe authoring of its motions.
#include "scene/figure.hpp"

#include <cmath>

#include "core/error.hpp"
#include "io/json_reader.hpp"
#include "core/track.hpp"

namespace vdc {

Skeleton figure_skeleton(double height) {
  const double s = height / 1.75;
  Skeleton k;
  const std::vector<Channel> rot{Channel::ZRotation, Channel::XRotation, Channel::YRotation};
  auto add = [&](const std::string& name, int parent, Vec3 offset, bool end = false) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = s * offset;
    j.end_site = end;
    if (!end) j.channels = rot;
    j.first_channel = k.num_channels;
    k.num_channels += static_cast<int>(j.channels.size());
    k.joints.push_back(j);
    return static_cast<int>(k.joints.size()) - 1;
  };
  Joint root;
  root.name = "Hips";
  root.offset = s * Vec3(0, 0.95, 0);
  root.channels = {Channel::XPosition, Channel::YPosition, Channel::ZPosition, Channel::ZRotation, Channel::XRotation, Channel::YRotation};
  k.joints.push_back(root);
  k.num_channels = 6;
  const int spine = add("Spine", 0, Vec3(0, 0.10, 0));
  const int chest = add("Chest", spine, Vec3(0, 0.20, 0));
  const int neck = add("Neck", chest, Vec3(0, 0.22, 0));
  const int head = add("Head", neck, Vec3(0, 0.09, 0.01));
  add("Head_end", head, Vec3(0, 0.13, 0), true);
  const double c = std::cos(50 * M_PI / 180), d = std::sin(50 * M_PI / 180);
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Left" : "Right";
    const int shoulder = add(p + "Shoulder", chest, Vec3(side * 0.03, 0.17, 0));
    const int arm = add(p + "Arm", shoulder, Vec3(side * 0.15, 0, 0));
    const int fore = add(p + "ForeArm", arm, Vec3(side * 0.28 * c, -0.28 * d, 0));
    const int hand = add(p + "Hand", fore, Vec3(side * 0.25 * c, -0.25 * d, 0));
    add(p + "Hand_end", hand, Vec3(side * 0.09 * c, -0.09 * d, 0), true);
  }
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Left" : "Right";
    const int up = add(p + "UpLeg", 0, Vec3(side * 0.09, -0.05, 0));
    const int leg = add(p + "Leg", up, Vec3(0, -0.42, 0));
    const int foot = add(p + "Foot", leg, Vec3(0, -0.42, 0));
    const int toe = add(p + "Toe", foot, Vec3(0, -0.05, 0.12));
    add(p + "Toe_end", toe, Vec3(0, 0, 0.05), true);
  }
  return k;
}

Motion author_motion(const Skeleton& skeleton, const std::vector<PoseKey>& keys, double fps, const std::string& name) {
  if (keys.empty()) throw InputError(name, "keys", "a motion needs at least one key");
  if (!(fps > 0)) throw InputError(name, "fps", "must be greater than 0");
  std::map<std::string, int> index;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) index[skeleton.joints[j].name] = static_cast<int>(j);
  std::vector<Vec3Track> rotation(skeleton.joints.size());
  Vec3Track root, root_rotation;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const PoseKey& key = keys[k];
    if (k > 0 && !(key.time > keys[k - 1].time)) throw InputError(name, "keys[" + std::to_string(k) + "].time", "keyframe times must increase");
    for (const auto& [joint, angles] : key.rotation) {
      auto it = index.find(joint);
      if (it == index.end() || skeleton.joints[static_cast<std::size_t>(it->second)].end_site || it->second == 0)
        throw InputError(name, "keys[" + std::to_string(k) + "].rotation." + joint, "no such joint (use root_rotation for Hips)");
    }
    for (std::size_t j = 1; j < skeleton.joints.size(); ++j) {
      auto it = key.rotation.find(skeleton.joints[j].name);
      rotation[j].keys.push_back({key.time, it == key.rotation.end() ? Vec3::Zero() : it->second});
    }
    root.keys.push_back({key.time, key.root});
    root_rotation.keys.push_back({key.time, key.root_rotation});
  }
  Motion m;
  m.skeleton = skeleton;
  m.frame_time = 1.0 / fps;
  const int n = static_cast<int>(std::floor(keys.back().time * fps + 1e-9)) + 1;
  for (int f = 0; f < n; ++f) {
    const double t = f / fps;
    std::vector<double> values(static_cast<std::size_t>(skeleton.num_channels), 0.0);
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const Joint& joint = skeleton.joints[j];
      const Vec3 angles = j == 0 ? root_rotation.at(t) : rotation[j].at(t);
      const Vec3 position = j == 0 ? root.at(t) : Vec3::Zero();
      for (std::size_t c = 0; c < joint.channels.size(); ++c) {
        double& v = values[static_cast<std::size_t>(joint.first_channel) + c];
        switch (joint.channels[c]) {
          case Channel::XPosition: v = position.x(); break;
          case Channel::YPosition: v = position.y(); break;
          case Channel::ZPosition: v = position.z(); break;
          case Channel::XRotation: v = angles.x(); break;
          case Channel::YRotation: v = angles.y(); break;
          case Channel::ZRotation: v = angles.z(); break;
        }
      }
    }
    m.frames.push_back(std::move(values));
  }
  return m;
}

Motion author_motion_file(const std::string& path) {
  JsonValue j = JsonValue::load_file(path);
  j.only_keys({"fps", "height", "keys"});
  const double fps = j.positive_or("fps", 30);
  const double height = j.positive_or("height", 1.75);
  std::vector<PoseKey> keys;
  for (const JsonValue& k : j.at("keys").items()) {
    k.only_keys({"time", "root", "root_rotation", "rotation"});
    PoseKey key;
    key.time = k.at("time").non_negative();
    key.root = k.vec3_or("root", Vec3::Zero());
    key.root_rotation = k.vec3_or("root_rotation", Vec3::Zero());
    if (auto r = k.find("rotation"))
      for (const auto& [joint, value] : r->members()) key.rotation.emplace(joint, value.vec3());
    keys.push_back(key);
  }
  return author_motion(figure_skeleton(height), keys, fps, path);
}

}  // namespace vdc
