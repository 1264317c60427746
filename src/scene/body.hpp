// Procedural body: a closed, watertight, consistently oriented triangle mesh of a figure built
// from a skeleton in its rest pose (tapered capsules along the bones, blended by a smooth
// minimum so the joints are smooth, polygonized once), skinned to the skeleton by linear blend
// skinning. Collisions treat it as one obstacle whose vertices move with the skin.
#pragma once
#include <map>
#include <vector>

#include "core/mesh_build.hpp"
#include "scene/skeleton.hpp"

namespace vdc {

// One joint's pull on a skin vertex: linear blend skinning moves the vertex to
// sum(weight * world(joint) * local) (the weights of a vertex summing to 1).
struct SkinWeight {
  int joint = 0;
  double weight = 0;
  Vec3 local = Vec3::Zero();  // the vertex in the joint's rest frame
};

// A character's own skin: a mesh of the figure in the skeleton's rest pose, with the weights it
// was rigged with (per position), or none for automatic weights.
struct Skin {
  MeshSource mesh;
  std::vector<std::vector<SkinWeight>> weights;
};

struct BodyParams {
  double build = 1.0;        // scales every limb's thickness
  double resolution = 0.025; // m: grid spacing of the polygonization
  double blend = 0.04;       // m: smooth-minimum width at the joints
};

// The thinnest build build_clearing_arms chooses.
inline constexpr double kSlimmestBuild = 0.6;

// The largest build, at most 1 and at least kSlimmestBuild, at which the arms' capsules (from the
// upper arms down, scene/humanoid.hpp) keep `clearance` (m) from the torso's and legs' (all but
// the clavicles', neck's and head's) in each of `poses`: a slender capture's arms, hanging at
// its sides, would otherwise pass through a body made for the project's figure, and no cloth
// could lie between. 1 for a skeleton that is not a humanoid's.
double build_clearing_arms(const Motion& motion, const std::vector<Pose>& poses, double clearance);

// Procedural rest meshes already polygonized, by the capsules and parameters they were made
// from (compared exactly): the copies of a crowd share one figure, and polygonizing it is most
// of a character's loading (about 50 ms at 3.5 cm).
class BodyMeshCache {
 public:
  const MeshSource* find(const std::vector<double>& key) const {
    const auto it = meshes_.find(key);
    return it == meshes_.end() ? nullptr : &it->second;
  }
  void add(std::vector<double> key, MeshSource mesh) { meshes_.emplace(std::move(key), std::move(mesh)); }
  std::size_t size() const { return meshes_.size(); }

 private:
  std::map<std::vector<double>, MeshSource> meshes_;
};

class Body {
 public:
  // The procedural body of the motion's skeleton in its rest pose (all rotations zero, offsets
  // as given); lengths in metres. With `cache`, a figure polygonized before is taken from it
  // (the same mesh, bit for bit) and a new one added to it.
  Body(const Motion& motion, const BodyParams& params, BodyMeshCache* cache = nullptr);
  // A given skin (a mesh of the figure in the skeleton's rest pose, same units) skinned to the
  // skeleton with the same automatic weights; params.build and params.blend shape the weights.
  Body(const Motion& motion, const BodyParams& params, MeshSource skin);
  // A given skin with its own weights (Skin::weights not empty): its rest positions are the
  // blend of its weights at the rest pose.
  Body(const Motion& motion, Skin skin);
  const MeshSource& rest_mesh() const { return rest_; }
  // Vertex positions for a pose; at the rest pose, exactly the rest mesh.
  std::vector<Vec3> skin(const Pose& pose) const;
  // Per vertex, the joint with the largest skinning weight (index into the skeleton).
  const std::vector<int>& main_joints() const { return main_joints_; }
  // The rest pose of the motion's skeleton.
  static Pose rest_pose(const Skeleton& s);

 private:
  struct Influence {  // a SkinWeight with its rest position
    int joint;        // the joint whose transform moves the vertex
    double weight;
    Vec3 local;       // the vertex in that joint's rest frame
    Vec3 rest_world;  // that joint's rest transform applied to `local`
  };
  Body(const Motion& motion, const BodyParams& params, MeshSource* skin, BodyMeshCache* cache);
  const Motion& motion_;
  MeshSource rest_;
  std::vector<std::vector<Influence>> influences_;  // per vertex
  std::vector<int> main_joints_;                    // per vertex
};

}  // namespace vdc
