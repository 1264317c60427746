// Artists' scene files through libassimp (model_file.hpp).
#include "scene/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

#include <assimp/BaseImporter.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>

#include "core/error.hpp"

namespace vdc {

namespace {

// A node's local transform from a clip channel at time `ticks`.
Eigen::Matrix4d channel_at(const aiNodeAnim& ch, double ticks) {
  auto vector_at = [&](const aiVectorKey* keys, unsigned n, const Vec3& none) -> Vec3 {
    if (n == 0) return none;
    if (ticks <= keys[0].mTime) return to_eigen(keys[0].mValue);
    for (unsigned k = 1; k < n; ++k)
      if (ticks < keys[k].mTime) {
        const double s = (ticks - keys[k - 1].mTime) / (keys[k].mTime - keys[k - 1].mTime);
        return (1 - s) * to_eigen(keys[k - 1].mValue) + s * to_eigen(keys[k].mValue);
      }
    return to_eigen(keys[n - 1].mValue);
  };
  auto quaternion = [](const aiQuaternion& q) { return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized(); };
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const aiQuatKey* keys = ch.mRotationKeys;
  const unsigned n = ch.mNumRotationKeys;
  if (n > 0) {
    q = quaternion(keys[n - 1].mValue);
    if (ticks <= keys[0].mTime) q = quaternion(keys[0].mValue);
    else
      for (unsigned k = 1; k < n; ++k)
        if (ticks < keys[k].mTime) {
          const double s = (ticks - keys[k - 1].mTime) / (keys[k].mTime - keys[k - 1].mTime);
          q = quaternion(keys[k - 1].mValue).slerp(s, quaternion(keys[k].mValue));
          break;
        }
  }
  Eigen::Affine3d local = Eigen::Affine3d::Identity();
  local.translate(vector_at(ch.mPositionKeys, ch.mNumPositionKeys, Vec3::Zero()));
  local.rotate(q);
  local.scale(vector_at(ch.mScalingKeys, ch.mNumScalingKeys, Vec3::Ones()));
  return local.matrix();
}

// From file units and axes to metres, y up: what FBX states in its metadata (assimp delivers
// FBX in centimetres and leaves its axes: the file's right, up and front axes, each an axis and a
// sign, become x, y and z); other formats are converted by the importer already.
Eigen::Matrix4d file_conversion(const aiScene& scene) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Identity();
  const aiMetadata* meta = scene.mMetaData;
  aiString format;
  if (!meta || !meta->Get("SourceAsset_Format", format) || std::string(format.C_Str()).find("FBX") == std::string::npos) return c;
  int axis[3] = {0, 1, 2}, sign[3] = {1, 1, 1};  // right (coord), up, front: FBX's y-up default
  meta->Get("CoordAxis", axis[0]);
  meta->Get("CoordAxisSign", sign[0]);
  meta->Get("UpAxis", axis[1]);
  meta->Get("UpAxisSign", sign[1]);
  meta->Get("FrontAxis", axis[2]);
  meta->Get("FrontAxisSign", sign[2]);
  Mat3 r = Mat3::Zero();
  for (int k = 0; k < 3; ++k) {
    if (axis[k] < 0 || axis[k] > 2) return c.topLeftCorner<3, 3>() *= 0.01, c;  // unstated: as delivered
    r(k, axis[k]) = sign[k] < 0 ? -1.0 : 1.0;
  }
  if (std::abs(r.determinant()) != 1) r = Mat3::Identity();  // two roles on one axis: as delivered
  c.topLeftCorner<3, 3>() = 0.01 * r;
  return c;
}

// Only the importers of the formats rigged characters come in: a file another would take by its
// content (a BVH, an OBJ, a scan) is refused rather than guessed at.
void keep_character_formats(Assimp::Importer& importer) {
  const std::set<std::string> kept{"Direct3D XFile Importer", "Valve SMD Importer", "Collada Importer", "Autodesk FBX Importer",
                                   "glTF Importer", "glTF2 Importer"};
  std::vector<Assimp::BaseImporter*> others;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i)
    if (!kept.count(importer.GetImporterInfo(i)->mName)) others.push_back(importer.GetImporter(i));
  for (Assimp::BaseImporter* other : others) {
    importer.UnregisterLoader(other);
    delete other;  // the importer deletes only the loaders it still holds
  }
}

// The file's bytes if it is text (no NUL byte), else nothing: a binary file's nesting is its
// records', not its bytes'.
std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return bytes.find('\0') == std::string::npos ? bytes : std::string();
}

// How deep a text's brackets ({ [ of JSON and X files, outside strings) and XML elements nest:
// the importers parse nesting by recursion, and a hostile file nested a million deep would end
// the program on its stack instead of in an error.
int deepest_nesting(const std::string& text) {
  int depth = 0, deepest = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '\\') ++i;
      else if (c == '"') quoted = false;
      continue;
    }
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    if (c == '"') quoted = true;
    else if (c == '{' || c == '[' || (c == '<' && std::isalpha(static_cast<unsigned char>(next)))) deepest = std::max(deepest, ++depth);
    else if (c == '}' || c == ']' || (c == '<' && next == '/') || (c == '/' && next == '>')) --depth;
  }
  return deepest;
}

const aiScene* read_scene(Assimp::Importer& importer, const std::string& path) {
  constexpr int kDeepestNesting = 1000;
  if (const int depth = deepest_nesting(text_of(path)); depth > kDeepestNesting)
    throw InputError(path, "", "nested " + std::to_string(depth) + " levels deep (no character or camera file is deeper than " +
                                   std::to_string(kDeepestNesting) + ")");
  keep_character_formats(importer);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) throw InputError(path, "", std::string("cannot read the file: ") + shortened(importer.GetErrorString()));
  return scene;
}

}  // namespace

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out(r, c) = m[r][c];
  return out;
}

Vec3 to_eigen(const aiVector3D& v) { return Vec3(v.x, v.y, v.z); }

NodeTable::NodeTable(const aiNode* root) {  // without recursion: a hierarchy may be deep
  std::vector<std::pair<const aiNode*, int>> stack{{root, -1}};
  while (!stack.empty()) {
    const auto [n, p] = stack.back();
    stack.pop_back();
    const int i = static_cast<int>(nodes.size());
    nodes.push_back(n);
    parent.push_back(p);
    by_name.emplace(n->mName.C_Str(), i);
    for (unsigned c = n->mNumChildren; c-- > 0;) stack.push_back({n->mChildren[c], i});
  }
}

ModelFile::ModelFile(const std::string& path)
    : path_(path), scene_(read_scene(importer_, path)), nodes_(scene_->mRootNode), conversion_(file_conversion(*scene_)) {}

std::string ModelFile::format() const {
  aiString format;
  return scene_->mMetaData && scene_->mMetaData->Get("SourceAsset_Format", format) ? format.C_Str() : "";
}

const aiAnimation* ModelFile::clip(const ClipChoice& choice) const {
  const aiScene& scene = *scene_;
  std::string names;
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) names += std::string(a ? ", '" : "'") + scene.mAnimations[a]->mName.C_Str() + "'";
  if (const auto* name = std::get_if<std::string>(&choice)) {
    for (unsigned a = 0; a < scene.mNumAnimations; ++a)
      if (*name == scene.mAnimations[a]->mName.C_Str()) return scene.mAnimations[a];
    throw InputError(path_, "", "no clip named '" + shortened(*name) + "'" + (names.empty() ? " (the file has no clips)" : " (its clips: " + names + ")"));
  }
  if (const auto* index = std::get_if<long long>(&choice)) {
    if (*index < 0 || *index >= static_cast<long long>(scene.mNumAnimations))
      throw InputError(path_, "", "no clip " + std::to_string(*index) + " (the file has " + std::to_string(scene.mNumAnimations) + ")");
    return scene.mAnimations[*index];
  }
  return scene.mNumAnimations ? scene.mAnimations[0] : nullptr;
}

std::vector<const aiNodeAnim*> ModelFile::channels(const aiAnimation* clip) const {
  std::vector<const aiNodeAnim*> out(nodes_.nodes.size(), nullptr);
  if (clip)
    for (unsigned c = 0; c < clip->mNumChannels; ++c)
      if (auto it = nodes_.by_name.find(clip->mChannels[c]->mNodeName.C_Str()); it != nodes_.by_name.end())
        out[static_cast<std::size_t>(it->second)] = clip->mChannels[c];
  return out;
}

std::vector<Eigen::Matrix4d> ModelFile::globals_at(const std::vector<const aiNodeAnim*>& channels, double tick) const {
  const NodeTable& t = nodes_;
  std::vector<Eigen::Matrix4d> g(t.nodes.size());
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    const Eigen::Matrix4d local = channels[i] ? channel_at(*channels[i], tick) : to_eigen(t.nodes[i]->mTransformation);
    g[i] = (t.parent[i] < 0 ? conversion_ : g[static_cast<std::size_t>(t.parent[i])]) * local;
  }
  return g;
}

std::vector<double> ModelFile::sample_ticks(const aiAnimation& clip) const {
  const double tps = ticks_per_second(clip);
  std::set<double> times;
  for (unsigned c = 0; c < clip.mNumChannels; ++c) {
    const aiNodeAnim& ch = *clip.mChannels[c];
    for (unsigned k = 0; k < ch.mNumPositionKeys; ++k) times.insert(ch.mPositionKeys[k].mTime);
    for (unsigned k = 0; k < ch.mNumRotationKeys; ++k) times.insert(ch.mRotationKeys[k].mTime);
    for (unsigned k = 0; k < ch.mNumScalingKeys; ++k) times.insert(ch.mScalingKeys[k].mTime);
  }
  if (times.size() < 2) return {times.empty() ? 0.0 : *times.begin()};
  const double first = *times.begin(), last = *times.rbegin();
  double step = last - first;
  for (auto it = std::next(times.begin()); it != times.end(); ++it) step = std::min(step, *it - *std::prev(it));
  bool on_grid = true;
  for (double t : times) on_grid = on_grid && std::abs((t - first) / step - std::round((t - first) / step)) < 1e-6;
  constexpr double kFinestStep = 1.0 / 240, kCoarseStep = 1.0 / 60;  // s
  if (!on_grid || step < kFinestStep * tps) step = kCoarseStep * tps;
  constexpr double kMostClipSamples = 200000;
  if ((last - first) / step > kMostClipSamples) step = (last - first) / kMostClipSamples;
  std::vector<double> out;
  const auto n = static_cast<long long>(std::ceil((last - first) / step - 1e-9));
  for (long long k = 0; k <= n; ++k) out.push_back(std::min(last, first + static_cast<double>(k) * step));
  return out;
}

}  // namespace vdc
