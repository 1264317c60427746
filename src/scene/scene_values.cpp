#include "scene/scene_values.hpp"

#include <filesystem>

namespace vdc {

namespace fs = std::filesystem;

std::string resolve_file(const JsonValue& j, const std::string& scene_path) {
  std::string rel = j.string();
  if (rel.empty()) j.fail("empty file name");
  fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(scene_path).parent_path() / rel;
  std::error_code ec;
  const fs::file_status status = fs::status(p, ec);
  if (!fs::exists(status)) {
    // A name the system cannot look up (too long, a loop of links) is named with the reason.
    const bool absent = !ec || ec == std::errc::no_such_file_or_directory || ec == std::errc::not_a_directory;
    j.fail((absent ? std::string("file not found") : "cannot look up the file (" + ec.message() + ")") + ": " + shortened(p.string()));
  }
  if (!fs::is_regular_file(status)) j.fail("not a regular file: " + shortened(p.string()));
  return p.string();
}

Vec3Track parse_track(const JsonValue& list, const char* name) {
  Vec3Track track;
  for (const JsonValue& k : list.items()) {
    k.only_keys({"time", name});
    Vec3Key key{k.at("time").non_negative(), k.at(name).vec3()};
    if (!track.keys.empty() && !(key.time > track.keys.back().time)) k.at("time").fail("keyframe times must increase");
    track.keys.push_back(key);
  }
  return track;
}

Transform parse_transform(const JsonValue& j) {
  j.only_keys({"scale", "rotate", "translate"});
  Transform t;
  t.scale = j.positive_or("scale", 1.0);
  t.rotate_degrees = j.vec3_or("rotate", Vec3::Zero());
  t.translate = j.vec3_or("translate", Vec3::Zero());
  return t;
}

void check_name(const JsonValue& where, const std::string& name, std::set<std::string>& seen) {
  if (name.empty() || name.find_first_of("/\\ \t.") != std::string::npos)
    where.fail("names must be non-empty, without spaces, dots or slashes (they name output files)");
  if (!seen.insert(name).second) where.fail("name '" + name + "' is used twice");
}

}  // namespace vdc
