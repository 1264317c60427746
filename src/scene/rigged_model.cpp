// Rigged characters from artists' files through libassimp (rigged_model.hpp): the node
// hierarchy evaluated as the importer's own convention does (a node's clip channel replaces its
// transform; keys between interpolated linearly and rotations by spherical interpolation; held
// before the first key and after the last), re-expressed in BVH conventions, and the skin blended
// by the file's weights (linear blend skinning).
#include "scene/rigged_model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/error.hpp"
#include "core/surface_repair.hpp"

namespace vdc {

namespace {

// A similarity transform: x -> scale * rotation * x + translation.
struct Similarity {
  double scale = 1;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Vec3 translation = Vec3::Zero();
};

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out(r, c) = m[r][c];
  return out;
}

Vec3 to_eigen(const aiVector3D& v) { return Vec3(v.x, v.y, v.z); }

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

// The file's nodes in depth-first order, parents first.
struct NodeTable {
  std::vector<const aiNode*> nodes;
  std::vector<int> parent;
  std::map<std::string, int> by_name;  // the first node of each name
  explicit NodeTable(const aiNode* root) {  // without recursion: a hierarchy may be deep
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
};

// Every node's global transform (with the file-to-scene conversion) at clip time `ticks`, or in
// the default pose when there is no clip.
std::vector<Eigen::Matrix4d> globals_at(const NodeTable& t, const std::vector<const aiNodeAnim*>& channel, double ticks,
                                        const Eigen::Matrix4d& conversion) {
  std::vector<Eigen::Matrix4d> g(t.nodes.size());
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    const Eigen::Matrix4d local = channel[i] ? channel_at(*channel[i], ticks) : to_eigen(t.nodes[i]->mTransformation);
    g[i] = (t.parent[i] < 0 ? conversion : g[static_cast<std::size_t>(t.parent[i])]) * local;
  }
  return g;
}

// A global transform as a similarity; throws naming the node for one that is not.
Similarity similarity(const Eigen::Matrix4d& m, const std::string& path, const std::string& node) {
  const Mat3 a = m.topLeftCorner<3, 3>();
  const Vec3 s(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
  if (!(s.minCoeff() > 0) || !std::isfinite(s.maxCoeff()))
    throw InputError(path, "node '" + node + "'", "its transform collapses or is not finite");
  if (s.maxCoeff() - s.minCoeff() > 1e-4 * s.maxCoeff())
    throw InputError(path, "node '" + node + "'", "a skeleton's joints must scale the same in every direction (its scale is " +
                                                      std::to_string(s.x()) + ", " + std::to_string(s.y()) + ", " + std::to_string(s.z()) + ")");
  if (a.determinant() < 0) throw InputError(path, "node '" + node + "'", "its transform mirrors (a negative scale), which a skeleton cannot follow");
  Similarity out;
  out.scale = s.mean();
  const Mat3 r = a / out.scale;
  Eigen::JacobiSVD<Mat3> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);  // the nearest rotation
  out.rotation = Eigen::Quaterniond(svd.matrixU() * svd.matrixV().transpose()).normalized();
  out.translation = m.topRightCorner<3, 1>();
  return out;
}

// From file units and axes to metres, y up: what FBX states in its metadata (assimp delivers
// FBX in centimetres and leaves its axes); other formats are converted by the importer already.
Eigen::Matrix4d file_conversion(const aiScene& scene) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Identity();
  const aiMetadata* meta = scene.mMetaData;
  aiString format;
  if (!meta || !meta->Get("SourceAsset_Format", format) || std::string(format.C_Str()).find("FBX") == std::string::npos) return c;
  c.topLeftCorner<3, 3>() *= 0.01;
  int up = 1, sign = 1;
  meta->Get("UpAxis", up);
  meta->Get("UpAxisSign", sign);
  Mat3 r = Mat3::Identity();
  const double q = sign < 0 ? -1.0 : 1.0;
  if (up == 2) r = Eigen::AngleAxisd(-q * M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  if (up == 0) r = Eigen::AngleAxisd(q * M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  if (up == 1 && sign < 0) r = Eigen::AngleAxisd(M_PI, Vec3::UnitX()).toRotationMatrix();
  c.topLeftCorner<3, 3>() = r * c.topLeftCorner<3, 3>();
  return c;
}

const aiAnimation* chosen_clip(const aiScene& scene, const ClipChoice& clip, const std::string& path) {
  std::string names;
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) names += std::string(a ? ", '" : "'") + scene.mAnimations[a]->mName.C_Str() + "'";
  if (const auto* name = std::get_if<std::string>(&clip)) {
    for (unsigned a = 0; a < scene.mNumAnimations; ++a)
      if (*name == scene.mAnimations[a]->mName.C_Str()) return scene.mAnimations[a];
    throw InputError(path, "", "no clip named '" + shortened(*name) + "'" + (names.empty() ? " (the file has no clips)" : " (its clips: " + names + ")"));
  }
  if (const auto* index = std::get_if<long long>(&clip)) {
    if (*index < 0 || *index >= static_cast<long long>(scene.mNumAnimations))
      throw InputError(path, "", "no clip " + std::to_string(*index) + " (the file has " + std::to_string(scene.mNumAnimations) + ")");
    return scene.mAnimations[*index];
  }
  return scene.mNumAnimations ? scene.mAnimations[0] : nullptr;
}

// The clip's sample times (ticks): its keys all lie on a grid of its smallest key spacing (a
// baked clip), then on that grid, which the interpolation between samples reproduces exactly;
// else every 1/60 s.
std::vector<double> sample_ticks(const aiAnimation& clip, double ticks_per_second) {
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
  if (!on_grid || step < kFinestStep * ticks_per_second) step = kCoarseStep * ticks_per_second;
  constexpr double kMostSamples = 200000;
  if ((last - first) / step > kMostSamples) step = (last - first) / kMostSamples;
  std::vector<double> out;
  const auto n = static_cast<long long>(std::ceil((last - first) / step - 1e-9));
  for (long long k = 0; k <= n; ++k) out.push_back(std::min(last, first + static_cast<double>(k) * step));
  return out;
}

// The joints: nodes that a bone or a mesh hangs from, with their ancestors up to the one they
// all share (the nodes above it only place the figure), and the nodes below a bone that carry
// nothing (a chain's end, e.g. a head's top).
std::vector<char> joint_nodes(const NodeTable& t, const std::set<int>& anchors) {
  std::vector<char> joint(t.nodes.size(), 0);
  std::vector<int> under(t.nodes.size(), 0);  // anchors at or below each node
  for (int a : anchors)
    for (int n = a; n >= 0; n = t.parent[static_cast<std::size_t>(n)]) ++under[static_cast<std::size_t>(n)];
  const auto all = static_cast<int>(anchors.size());
  // The shared ancestor: the deepest node that holds every anchor.
  int top = 0;
  for (std::size_t n = 0; n < t.nodes.size(); ++n)
    if (under[n] == all) top = static_cast<int>(n);  // depth-first order: a holder's holders come before it
  for (int a : anchors)
    for (int n = a; n >= 0 && !joint[static_cast<std::size_t>(n)]; n = t.parent[static_cast<std::size_t>(n)]) {
      joint[static_cast<std::size_t>(n)] = 1;
      if (n == top) break;
    }
  std::vector<char> below_anchor(t.nodes.size(), 0);
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    const int p = t.parent[i];
    below_anchor[i] = p >= 0 && (below_anchor[static_cast<std::size_t>(p)] || anchors.count(p));
    if (below_anchor[i] && t.nodes[i]->mNumMeshes == 0 && joint[static_cast<std::size_t>(p)]) joint[i] = 1;
  }
  return joint;
}

// The skin made a surface collisions can work with (surface_repair.hpp), the weights following
// the positions copied; what was found noted.
RiggedModel repaired(RiggedModel model, const std::string& path) {
  RepairedSurface r = [&] {
    try {
      return repair_surface(model.skin);
    } catch (const MeshBuildError& e) {
      throw InputError(path, "", std::string("the skin cannot be a collision surface: ") + e.what());
    }
  }();
  std::vector<std::vector<SkinWeight>> weights;
  for (int32_t p : r.source) weights.push_back(model.weights[static_cast<std::size_t>(p)]);
  model.skin = std::move(r.mesh);
  model.weights = std::move(weights);
  if (const std::string found = r.repairs.summary(); !found.empty()) model.notes.push_back(path + ": the character's skin: " + found);
  return model;
}

}  // namespace

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

RiggedModel read_rigged_model(const std::string& path, const ClipChoice& clip_choice) {
  constexpr int kDeepestNesting = 1000;
  if (const int depth = deepest_nesting(text_of(path)); depth > kDeepestNesting)
    throw InputError(path, "", "nested " + std::to_string(depth) + " levels deep (no character file is deeper than " + std::to_string(kDeepestNesting) + ")");
  Assimp::Importer importer;
  keep_character_formats(importer);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) throw InputError(path, "", std::string("cannot read the file: ") + shortened(importer.GetErrorString()));
  RiggedModel model;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) model.clips.emplace_back(scene->mAnimations[a]->mName.C_Str());
  const aiAnimation* clip = chosen_clip(*scene, clip_choice, path);

  const NodeTable table(scene->mRootNode);
  std::vector<const aiNodeAnim*> channel(table.nodes.size(), nullptr);
  if (clip)
    for (unsigned c = 0; c < clip->mNumChannels; ++c)
      if (auto it = table.by_name.find(clip->mChannels[c]->mNodeName.C_Str()); it != table.by_name.end())
        channel[static_cast<std::size_t>(it->second)] = clip->mChannels[c];

  // The meshes as the nodes place them; a skinned mesh hangs from its bones, another from its node.
  struct Placed {
    const aiMesh* mesh;
    int node;
  };
  std::vector<Placed> placed;
  std::set<int> anchors;
  for (std::size_t i = 0; i < table.nodes.size(); ++i)
    for (unsigned m = 0; m < table.nodes[i]->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[table.nodes[i]->mMeshes[m]];
      if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      placed.push_back({mesh, static_cast<int>(i)});
      if (mesh->mNumBones == 0) anchors.insert(static_cast<int>(i));
      for (unsigned b = 0; b < mesh->mNumBones; ++b) {
        const auto it = table.by_name.find(mesh->mBones[b]->mName.C_Str());
        if (it == table.by_name.end())
          throw InputError(path, std::string("mesh '") + mesh->mName.C_Str() + "'", std::string("its bone '") + mesh->mBones[b]->mName.C_Str() + "' is no node of the file");
        anchors.insert(it->second);
      }
    }
  if (placed.empty()) throw InputError(path, "", "the file has no triangles: a character needs a mesh");
  const std::vector<char> is_joint = joint_nodes(table, anchors);

  // Joints in the nodes' order (parents first), each under its nearest joint ancestor.
  std::vector<int> joint_of(table.nodes.size(), -1), node_of;
  Skeleton& skeleton = model.motion.skeleton;
  std::set<std::string> names;
  for (std::size_t i = 0; i < table.nodes.size(); ++i) {
    if (!is_joint[i]) continue;
    Joint j;
    j.name = table.nodes[i]->mName.C_Str();
    if (j.name.empty() || names.count(j.name)) j.name += "#" + std::to_string(i);
    names.insert(j.name);
    for (int p = table.parent[i]; p >= 0 && j.parent < 0; p = table.parent[static_cast<std::size_t>(p)]) j.parent = joint_of[static_cast<std::size_t>(p)];
    joint_of[i] = static_cast<int>(skeleton.joints.size());
    node_of.push_back(static_cast<int>(i));
    skeleton.joints.push_back(std::move(j));
  }

  // The default pose and the clip's samples, as similarities per joint.
  const Eigen::Matrix4d conversion = file_conversion(*scene);
  const std::vector<const aiNodeAnim*> none(table.nodes.size(), nullptr);
  const std::vector<Eigen::Matrix4d> rest_globals = globals_at(table, none, 0, conversion);
  std::vector<Similarity> rest;
  for (int n : node_of) rest.push_back(similarity(rest_globals[static_cast<std::size_t>(n)], path, table.nodes[static_cast<std::size_t>(n)]->mName.C_Str()));
  const double ticks_per_second = clip && clip->mTicksPerSecond > 0 ? clip->mTicksPerSecond : 25.0;
  const std::vector<double> ticks = clip ? sample_ticks(*clip, ticks_per_second) : std::vector<double>{0.0};
  std::vector<std::vector<Similarity>> samples;
  for (double t : ticks) {
    const std::vector<Eigen::Matrix4d> g = clip ? globals_at(table, channel, t, conversion) : rest_globals;
    std::vector<Similarity>& s = samples.emplace_back();
    for (std::size_t j = 0; j < node_of.size(); ++j) {
      const std::string name = table.nodes[static_cast<std::size_t>(node_of[j])]->mName.C_Str();
      s.push_back(similarity(g[static_cast<std::size_t>(node_of[j])], path, name));
      if (std::abs(s.back().scale - rest[j].scale) > 1e-4 * rest[j].scale)
        throw InputError(path, "node '" + name + "'", "the clip changes its scale, which a skeleton cannot follow");
    }
  }
  if (ticks.size() > 1) model.motion.frame_time = (ticks[1] - ticks[0]) / ticks_per_second;

  // BVH conventions: joint frames aligned with the world in the default pose (rotation
  // R(t) * R(rest)^-1), offsets and position channels in the parent's frame.
  auto world_rotation = [&](const std::vector<Similarity>& s, int j) { return s[static_cast<std::size_t>(j)].rotation * rest[static_cast<std::size_t>(j)].rotation.conjugate(); };
  auto local_of = [&](const std::vector<Similarity>& s, int j) {
    const int p = skeleton.joints[static_cast<std::size_t>(j)].parent;
    const Eigen::Quaterniond qp = p < 0 ? Eigen::Quaterniond::Identity() : world_rotation(s, p);
    const Vec3 tp = p < 0 ? Vec3::Zero() : s[static_cast<std::size_t>(p)].translation;
    return std::pair{(qp.conjugate() * world_rotation(s, j)).normalized(), Vec3(qp.conjugate() * (s[static_cast<std::size_t>(j)].translation - tp))};
  };
  const double extent = [&] {
    Aabb box;
    for (const Similarity& s : rest) box.grow(s.translation);
    return std::max((box.hi - box.lo).norm(), 1e-12);
  }();
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    Joint& joint = skeleton.joints[j];
    joint.offset = local_of(rest, static_cast<int>(j)).second;
    bool moves = joint.parent < 0;
    for (const auto& s : samples) moves = moves || (local_of(s, static_cast<int>(j)).second - joint.offset).norm() > 1e-9 * extent;
    joint.first_channel = skeleton.num_channels;
    if (moves) joint.channels = {Channel::XPosition, Channel::YPosition, Channel::ZPosition};
    joint.channels.insert(joint.channels.end(), {Channel::ZRotation, Channel::YRotation, Channel::XRotation});
    skeleton.num_channels += static_cast<int>(joint.channels.size());
  }
  for (const auto& s : samples) {
    std::vector<double>& values = model.motion.frames.emplace_back();
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const auto [q, t] = local_of(s, static_cast<int>(j));
      if (skeleton.joints[j].channels.size() == 6)
        for (int k = 0; k < 3; ++k) values.push_back(t[k] - skeleton.joints[j].offset[k]);
      const Vec3 zyx = q.toRotationMatrix().eulerAngles(2, 1, 0) * (180.0 / M_PI);
      values.insert(values.end(), {zyx[0], zyx[1], zyx[2]});
    }
  }

  // The skin: every mesh's vertices at the default pose, positions that coincide made one.
  std::map<std::array<double, 3>, int32_t> welded;
  for (const Placed& p : placed) {
    const aiMesh& mesh = *p.mesh;
    const std::string where = std::string("mesh '") + mesh.mName.C_Str() + "'";
    std::vector<std::vector<SkinWeight>> pulls(mesh.mNumVertices);
    auto pull = [&](int node, const Eigen::Matrix4d& to_node, unsigned v, double w) {
      const int j = joint_of[static_cast<std::size_t>(node)];
      const Similarity& r = rest[static_cast<std::size_t>(j)];
      // world(rest) * local = the vertex where the node's default transform puts it.
      const Eigen::Vector4d x = rest_globals[static_cast<std::size_t>(node)] * to_node * Eigen::Vector4d(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z, 1);
      pulls[v].push_back({j, w, Vec3(x.head<3>()) - r.translation});
    };
    if (mesh.mNumBones == 0)
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) pull(p.node, Eigen::Matrix4d::Identity(), v, 1.0);
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
      const aiBone& bone = *mesh.mBones[b];
      const int node = table.by_name.at(bone.mName.C_Str());
      for (unsigned k = 0; k < bone.mNumWeights; ++k) {
        const aiVertexWeight& vw = bone.mWeights[k];
        if (vw.mVertexId >= mesh.mNumVertices || !(vw.mWeight >= 0) || !std::isfinite(vw.mWeight))
          throw InputError(path, where, std::string("bone '") + bone.mName.C_Str() + "' has a weight that is negative, not finite or for no vertex");
        if (vw.mWeight > 0) pull(node, to_eigen(bone.mOffsetMatrix), vw.mVertexId, vw.mWeight);
      }
    }
    std::vector<int32_t> index(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      double total = 0;
      for (const SkinWeight& w : pulls[v]) total += w.weight;
      if (!(total > 0)) throw InputError(path, where, "vertex " + std::to_string(v) + " has no skinning weight");
      Vec3 x = Vec3::Zero();
      for (SkinWeight& w : pulls[v]) {
        w.weight /= total;
        x += w.weight * (rest[static_cast<std::size_t>(w.joint)].translation + w.local);
      }
      if (!x.allFinite()) throw InputError(path, where, "vertex " + std::to_string(v) + " is not finite");
      const auto [it, added] = welded.emplace(std::array<double, 3>{x.x(), x.y(), x.z()}, static_cast<int32_t>(model.skin.positions.size()));
      if (added) {
        model.skin.positions.push_back(x);
        model.weights.push_back(std::move(pulls[v]));
      }
      index[v] = it->second;
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      const int32_t a = index[face.mIndices[0]], b = index[face.mIndices[1]], c = index[face.mIndices[2]];
      if (a == b || b == c || a == c) continue;
      model.skin.faces.push_back({Corner{a, 0}, Corner{b, 0}, Corner{c, 0}});
    }
  }
  if (model.skin.faces.empty()) throw InputError(path, "", "the file's meshes have no triangle with three distinct corners");
  return repaired(std::move(model), path);
}

}  // namespace vdc
