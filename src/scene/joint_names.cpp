#include "scene/joint_names.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <utility>
#include <vector>

namespace vdc {

std::string folded_joint_name(const std::string& name) {
  const std::size_t colon = name.rfind(':');
  std::string out;
  for (std::size_t i = colon == std::string::npos ? 0 : colon + 1; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c == '_' || c == '-' || c == '.' || std::isspace(c)) continue;
    out += static_cast<char>(std::tolower(c));
  }
  return out;
}

namespace {

// The project's joints of the trunk and head, with the other schemes' names, folded, in the
// order they are tried.
const std::vector<std::pair<std::string, std::vector<std::string>>>& trunk_aliases() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> table{
      {"hips", {"pelvis", "root", "hip"}},
      {"spine", {"lowerback", "spine0"}},
      {"chest", {"upperchest", "spine2", "spine1"}},
      {"neck", {"neck1"}},
      {"head", {}},
  };
  return table;
}

// A limb joint of one side, with the other schemes' names without the side, in order.
const std::vector<std::pair<std::string, std::vector<std::string>>>& limb_aliases() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> table{
      {"shoulder", {"collar", "clavicle"}},
      {"arm", {"upperarm"}},
      {"forearm", {"lowerarm", "elbow"}},
      {"hand", {"wrist"}},
      {"upleg", {"thigh", "upperleg"}},
      {"leg", {"lowerleg", "shin", "knee", "calf"}},
      {"foot", {"ankle"}},
      {"toe", {"toebase", "toes", "ball"}},
  };
  return table;
}

}  // namespace

std::vector<std::string> joint_aliases(const std::string& wanted) {
  const std::string folded = folded_joint_name(wanted);
  for (const auto& [name, others] : trunk_aliases())
    if (folded == name) return others;
  for (const auto& [side, short_side] : {std::pair<std::string, std::string>{"left", "l"}, {"right", "r"}}) {
    if (folded.rfind(side, 0) != 0) continue;
    const std::string part = folded.substr(side.size());
    for (const auto& [name, others] : limb_aliases()) {
      if (part != name) continue;
      std::vector<std::string> out{short_side + name};
      for (const std::string& other : others) {
        out.push_back(side + other);
        out.push_back(short_side + other);
      }
      return out;
    }
  }
  return {};
}

std::optional<int> find_joint(const Skeleton& skeleton, const std::string& wanted) {
  const auto& joints = skeleton.joints;
  auto index_of = [&](auto matches) -> std::optional<int> {
    const auto it = std::find_if(joints.begin(), joints.end(), matches);
    if (it == joints.end()) return std::nullopt;
    return static_cast<int>(it - joints.begin());
  };
  if (auto exact = index_of([&](const Joint& j) { return j.name == wanted; })) return exact;
  std::vector<std::string> names{folded_joint_name(wanted)};
  for (std::string& alias : joint_aliases(wanted)) names.push_back(std::move(alias));
  for (const std::string& name : names)
    if (auto found = index_of([&](const Joint& j) { return !j.end_site && folded_joint_name(j.name) == name; })) return found;
  return std::nullopt;
}

void rename_joints(Skeleton& skeleton, const std::map<std::string, std::string>& names) {
  // All found before any is renamed, so that {"a": "b", "b": "c"} swaps nothing into a chain.
  std::vector<std::pair<std::size_t, std::string>> renames;
  for (const auto& rename : names) {  // not a structured binding: clang 14 (make fuzz) cannot capture one
    const std::string& from = rename.first;
    const auto it = std::find_if(skeleton.joints.begin(), skeleton.joints.end(), [&](const Joint& j) { return j.name == from; });
    if (it == skeleton.joints.end()) throw std::invalid_argument(from);
    renames.emplace_back(static_cast<std::size_t>(it - skeleton.joints.begin()), rename.second);
  }
  for (auto& [index, to] : renames) skeleton.joints[index].name = std::move(to);
}

std::string missing_joint(const Skeleton& skeleton, const std::string& joint) {
  std::string msg = "the motion has no joint '" + joint + "'";
  const std::vector<std::string> aliases = joint_aliases(joint);
  if (!aliases.empty()) {
    msg += " (nor";
    for (std::size_t k = 0; k < aliases.size(); ++k) msg += (k ? ", " : " ") + aliases[k];
    msg += ")";
  }
  msg += "; its joints:";
  std::size_t listed = 0;
  for (const Joint& j : skeleton.joints) {
    if (j.end_site) continue;
    if (listed == 8) {
      msg += " ...";
      break;
    }
    msg += (listed++ ? ", " : " ") + j.name;
  }
  return msg + " (a character's joint_names renames a capture's joints)";
}

}  // namespace vdc
