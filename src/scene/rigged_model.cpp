// Rigged characters from artists' files (rigged_model.hpp): the file's nodes as ModelFile
// evaluates them, re-expressed in BVH conventions, and the skin blended by the file's weights
// (linear blend skinning).
#include "scene/rigged_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/bvh.hpp"
#include "core/error.hpp"
#include "core/surface_repair.hpp"
#include "scene/model_file.hpp"

namespace vdc {

namespace {

// A similarity transform: x -> scale * rotation * x + translation.
struct Similarity {
  double scale = 1;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Vec3 translation = Vec3::Zero();
};

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

// A mesh as the nodes place it: a skinned mesh hangs from its bones, another from its node.
struct PlacedMesh {
  const aiMesh* mesh;
  int node;
};

// The meshes of triangles in the file and the nodes they hang from.
std::vector<PlacedMesh> placed_meshes(const ModelFile& file, std::set<int>& anchors) {
  const NodeTable& table = file.nodes();
  std::vector<PlacedMesh> placed;
  for (std::size_t i = 0; i < table.nodes.size(); ++i)
    for (unsigned m = 0; m < table.nodes[i]->mNumMeshes; ++m) {
      const aiMesh* mesh = file.scene().mMeshes[table.nodes[i]->mMeshes[m]];
      if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      placed.push_back({mesh, static_cast<int>(i)});
      if (mesh->mNumBones == 0) anchors.insert(static_cast<int>(i));
      for (unsigned b = 0; b < mesh->mNumBones; ++b) {
        const auto it = table.by_name.find(mesh->mBones[b]->mName.C_Str());
        if (it == table.by_name.end())
          throw InputError(file.path(), std::string("mesh '") + mesh->mName.C_Str() + "'",
                           std::string("its bone '") + mesh->mBones[b]->mName.C_Str() + "' is no node of the file");
        anchors.insert(it->second);
      }
    }
  if (placed.empty()) throw InputError(file.path(), "", "the file has no triangles: a character needs a mesh");
  return placed;
}

// The skeleton's joints and their nodes, both ways.
struct JointNodes {
  std::vector<int> joint_of;  // per node, -1 for none
  std::vector<int> node_of;   // per joint
};

// Joints in the nodes' order (parents first), each under its nearest joint ancestor; names
// made unique.
JointNodes add_joints(const NodeTable& table, const std::vector<char>& is_joint, Skeleton& skeleton) {
  JointNodes out;
  out.joint_of.assign(table.nodes.size(), -1);
  std::set<std::string> names;
  for (std::size_t i = 0; i < table.nodes.size(); ++i) {
    if (!is_joint[i]) continue;
    Joint j;
    j.name = table.nodes[i]->mName.C_Str();
    if (j.name.empty() || names.count(j.name)) j.name += "#" + std::to_string(i);
    names.insert(j.name);
    for (int p = table.parent[i]; p >= 0 && j.parent < 0; p = table.parent[static_cast<std::size_t>(p)]) j.parent = out.joint_of[static_cast<std::size_t>(p)];
    out.joint_of[i] = static_cast<int>(skeleton.joints.size());
    out.node_of.push_back(static_cast<int>(i));
    skeleton.joints.push_back(std::move(j));
  }
  return out;
}

// The joints' similarities in one pose of the file's nodes.
std::vector<Similarity> joint_pose(const ModelFile& file, const JointNodes& joints, const std::vector<Eigen::Matrix4d>& globals) {
  std::vector<Similarity> out;
  for (int n : joints.node_of)
    out.push_back(similarity(globals[static_cast<std::size_t>(n)], file.path(), file.nodes().nodes[static_cast<std::size_t>(n)]->mName.C_Str()));
  return out;
}

// The clip's samples (the default pose alone without one), every joint's scale as at rest.
std::vector<std::vector<Similarity>> clip_samples(const ModelFile& file, const aiAnimation* clip, const JointNodes& joints,
                                                  const std::vector<Similarity>& rest, double& frame_time) {
  if (!clip) return {rest};
  const std::vector<double> ticks = file.sample_ticks(*clip);
  if (ticks.size() > 1) frame_time = (ticks[1] - ticks[0]) / ModelFile::ticks_per_second(*clip);
  const std::vector<const aiNodeAnim*> channels = file.channels(clip);
  std::vector<std::vector<Similarity>> samples;
  for (double t : ticks) {
    samples.push_back(joint_pose(file, joints, file.globals_at(channels, t)));
    for (std::size_t j = 0; j < rest.size(); ++j)
      if (std::abs(samples.back()[j].scale - rest[j].scale) > 1e-4 * rest[j].scale)
        throw InputError(file.path(), std::string("node '") + file.nodes().nodes[static_cast<std::size_t>(joints.node_of[j])]->mName.C_Str() + "'",
                         "the clip changes its scale, which a skeleton cannot follow");
  }
  return samples;
}

// The motion in BVH conventions: joint frames aligned with the world in the default pose
// (rotation R(t) R(rest)^-1), offsets and position channels in the parent's frame; position
// channels for the root and the joints the clip moves, ZYX rotation channels for all.
void fill_motion(const std::vector<Similarity>& rest, const std::vector<std::vector<Similarity>>& samples, Motion& motion) {
  Skeleton& skeleton = motion.skeleton;
  auto world_rotation = [&](const std::vector<Similarity>& s, int j) {
    return s[static_cast<std::size_t>(j)].rotation * rest[static_cast<std::size_t>(j)].rotation.conjugate();
  };
  auto local_of = [&](const std::vector<Similarity>& s, int j) {
    const int p = skeleton.joints[static_cast<std::size_t>(j)].parent;
    const Eigen::Quaterniond qp = p < 0 ? Eigen::Quaterniond::Identity() : world_rotation(s, p);
    const Vec3 tp = p < 0 ? Vec3::Zero() : s[static_cast<std::size_t>(p)].translation;
    return std::pair{(qp.conjugate() * world_rotation(s, j)).normalized(), Vec3(qp.conjugate() * (s[static_cast<std::size_t>(j)].translation - tp))};
  };
  Aabb box;
  for (const Similarity& s : rest) box.grow(s.translation);
  const double extent = std::max((box.hi - box.lo).norm(), 1e-12);
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
    std::vector<double>& values = motion.frames.emplace_back();
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const auto [q, t] = local_of(s, static_cast<int>(j));
      if (skeleton.joints[j].channels.size() == 6)
        for (int k = 0; k < 3; ++k) values.push_back(t[k] - skeleton.joints[j].offset[k]);
      const Vec3 zyx = q.toRotationMatrix().eulerAngles(2, 1, 0) * (180.0 / M_PI);
      values.insert(values.end(), {zyx[0], zyx[1], zyx[2]});
    }
  }
}

// Per vertex of a mesh, the joints that pull it with the file's weights (a mesh without bones
// follows its node), each with the vertex where the node's default transform puts it, relative
// to the joint (world(rest) * local is that place).
std::vector<std::vector<SkinWeight>> mesh_weights(const ModelFile& file, const PlacedMesh& p, const JointNodes& joints,
                                                  const std::vector<Similarity>& rest, const std::vector<Eigen::Matrix4d>& rest_globals) {
  const aiMesh& mesh = *p.mesh;
  std::vector<std::vector<SkinWeight>> pulls(mesh.mNumVertices);
  auto pull = [&](int node, const Eigen::Matrix4d& to_node, unsigned v, double w) {
    const int j = joints.joint_of[static_cast<std::size_t>(node)];
    const Eigen::Vector4d x = rest_globals[static_cast<std::size_t>(node)] * to_node * Eigen::Vector4d(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z, 1);
    pulls[v].push_back({j, w, Vec3(x.head<3>()) - rest[static_cast<std::size_t>(j)].translation});
  };
  if (mesh.mNumBones == 0)
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) pull(p.node, Eigen::Matrix4d::Identity(), v, 1.0);
  for (unsigned b = 0; b < mesh.mNumBones; ++b) {
    const aiBone& bone = *mesh.mBones[b];
    const int node = file.nodes().by_name.at(bone.mName.C_Str());
    for (unsigned k = 0; k < bone.mNumWeights; ++k) {
      const aiVertexWeight& vw = bone.mWeights[k];
      if (vw.mVertexId >= mesh.mNumVertices || !(vw.mWeight >= 0) || !std::isfinite(vw.mWeight))
        throw InputError(file.path(), std::string("mesh '") + mesh.mName.C_Str() + "'",
                         std::string("bone '") + bone.mName.C_Str() + "' has a weight that is negative, not finite or for no vertex");
      if (vw.mWeight > 0) pull(node, to_eigen(bone.mOffsetMatrix), vw.mVertexId, vw.mWeight);
    }
  }
  return pulls;
}

// Every mesh's vertices at the default pose, weights summing to 1, positions that coincide
// made one; faces with three distinct corners.
void fill_skin(const ModelFile& file, const std::vector<PlacedMesh>& placed, const JointNodes& joints, const std::vector<Similarity>& rest,
               RiggedModel& model) {
  const std::vector<Eigen::Matrix4d> rest_globals = file.globals_at(file.channels(nullptr), 0);
  std::map<std::array<double, 3>, int32_t> welded;
  for (const PlacedMesh& p : placed) {
    const aiMesh& mesh = *p.mesh;
    const std::string where = std::string("mesh '") + mesh.mName.C_Str() + "'";
    std::vector<std::vector<SkinWeight>> pulls = mesh_weights(file, p, joints, rest, rest_globals);
    std::vector<int32_t> index(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      double total = 0;
      for (const SkinWeight& w : pulls[v]) total += w.weight;
      if (!(total > 0)) throw InputError(file.path(), where, "vertex " + std::to_string(v) + " has no skinning weight");
      Vec3 x = Vec3::Zero();
      for (SkinWeight& w : pulls[v]) {
        w.weight /= total;
        x += w.weight * (rest[static_cast<std::size_t>(w.joint)].translation + w.local);
      }
      if (!x.allFinite()) throw InputError(file.path(), where, "vertex " + std::to_string(v) + " is not finite");
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
      if (a != b && b != c && a != c) model.skin.faces.push_back({Corner{a, 0}, Corner{b, 0}, Corner{c, 0}});
    }
  }
  if (model.skin.faces.empty()) throw InputError(file.path(), "", "the file's meshes have no triangle with three distinct corners");
}

}  // namespace

RiggedModel read_rigged_model(const std::string& path, const ClipChoice& clip_choice) {
  const ModelFile file(path);
  RiggedModel model;
  for (unsigned a = 0; a < file.scene().mNumAnimations; ++a) model.clips.emplace_back(file.scene().mAnimations[a]->mName.C_Str());
  const aiAnimation* clip = file.clip(clip_choice);
  std::set<int> anchors;
  const std::vector<PlacedMesh> placed = placed_meshes(file, anchors);
  const JointNodes joints = add_joints(file.nodes(), joint_nodes(file.nodes(), anchors), model.motion.skeleton);
  const std::vector<Similarity> rest = joint_pose(file, joints, file.globals_at(file.channels(nullptr), 0));
  fill_motion(rest, clip_samples(file, clip, joints, rest, model.motion.frame_time), model.motion);
  fill_skin(file, placed, joints, rest, model);
  return repaired(std::move(model), path);
}

}  // namespace vdc
