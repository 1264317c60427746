// An animation package's scene file read through libassimp, for the characters and cameras in
// it: only the importers of the formats characters and shots come in (glTF, FBX, Collada, X,
// SMD; another file is refused rather than guessed at), a text file's nesting checked before the
// importer's recursive parsers see it, its node hierarchy in depth-first order, and every node's
// global transform at any tick of a clip as the importer's convention has it: a node's clip
// channel replaces its transform, keys between are interpolated linearly and rotations by
// spherical interpolation, held before the first key and after the last.
#pragma once
#include <map>
#include <string>
#include <variant>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "core/math.hpp"

namespace vdc {

// A clip asked for by name or by index; the first clip when none is.
using ClipChoice = std::variant<std::monostate, std::string, long long>;

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m);
Vec3 to_eigen(const aiVector3D& v);

// The file's nodes in depth-first order, parents first.
struct NodeTable {
  explicit NodeTable(const aiNode* root);
  std::vector<const aiNode*> nodes;
  std::vector<int> parent;
  std::map<std::string, int> by_name;  // the first node of each name
};

class ModelFile {
 public:
  // Throws InputError(path, "", problem) for a file the importer cannot read or nested too deep.
  explicit ModelFile(const std::string& path);
  ModelFile(const ModelFile&) = delete;
  ModelFile& operator=(const ModelFile&) = delete;
  const aiScene& scene() const { return *scene_; }
  const std::string& path() const { return path_; }
  const NodeTable& nodes() const { return nodes_; }
  // The importer's name for the file's format ("glTF2 Importer", "Autodesk FBX Importer", ...).
  std::string format() const;
  // The clip asked for (none when the file has no clips and none was asked for); throws
  // InputError naming the clips there are.
  const aiAnimation* clip(const ClipChoice& choice) const;
  // Per node, its channel in `clip` (nullptr: none, or no clip).
  std::vector<const aiNodeAnim*> channels(const aiAnimation* clip) const;
  // Every node's global transform at `tick`, in metres with y up (conversion()).
  std::vector<Eigen::Matrix4d> globals_at(const std::vector<const aiNodeAnim*>& channels, double tick) const;
  // From file units and axes to metres, y up.
  const Eigen::Matrix4d& conversion() const { return conversion_; }
  // The clip's sample ticks: on the grid of its smallest key spacing when every key lies on it
  // (a baked clip, which interpolation between samples reproduces exactly), else every 1/60 s;
  // and its ticks per second (25 when the file does not say).
  std::vector<double> sample_ticks(const aiAnimation& clip) const;
  static double ticks_per_second(const aiAnimation& clip) { return clip.mTicksPerSecond > 0 ? clip.mTicksPerSecond : 25.0; }

 private:
  std::string path_;
  Assimp::Importer importer_;
  const aiScene* scene_ = nullptr;
  NodeTable nodes_;
  Eigen::Matrix4d conversion_;
};

}  // namespace vdc
