#include "scene/joint_names.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <utility>
#include <vector>

#include "scene/humanoid.hpp"

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

std::optional<int> find_joint(const Skeleton& skeleton, const std::string& wanted) {
  const auto& joints = skeleton.joints;
  auto index_of = [&](auto matches) -> std::optional<int> {
    const auto it = std::find_if(joints.begin(), joints.end(), matches);
    if (it == joints.end()) return std::nullopt;
    return static_cast<int>(it - joints.begin());
  };
  if (auto renamed = index_of([&](const Joint& j) { return j.named_by_scene && j.name == wanted; })) return renamed;
  const HumanoidRecognition figure = recognise_humanoid(skeleton);
  if (figure.humanoid)
    if (const std::optional<int> landmark = landmark_joint(*figure.humanoid, wanted)) {
      if (*landmark < 0) return std::nullopt;
      return landmark;
    }
  if (auto exact = index_of([&](const Joint& j) { return j.name == wanted; })) return exact;
  const std::string folded = folded_joint_name(wanted);
  return index_of([&](const Joint& j) { return !j.end_site && folded_joint_name(j.name) == folded; });
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
  for (auto& [index, to] : renames) {
    skeleton.joints[index].name = std::move(to);
    skeleton.joints[index].named_by_scene = true;
  }
}

std::string missing_joint(const Skeleton& skeleton, const std::string& joint) {
  const std::string how = " (a character's joint_names renames a capture's joints)";
  const HumanoidRecognition figure = recognise_humanoid(skeleton);
  if (landmark_joint(Humanoid{}, joint)) {
    if (!figure.humanoid) return "the motion's skeleton is not a humanoid's, so it has no '" + joint + "': " + figure.why_not + how;
    return "the motion's figure has no joint where '" + joint + "' is on the project's figure" + how;
  }
  std::string msg = "the motion has no joint '" + joint + "'; its joints:";
  std::size_t listed = 0;
  for (const Joint& j : skeleton.joints) {
    if (j.end_site) continue;
    if (listed == 8) {
      msg += " ...";
      break;
    }
    msg += (listed++ ? ", " : " ") + j.name;
  }
  return msg + how;
}

}  // namespace vdc
