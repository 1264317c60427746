// A rigged, animated character from an artist's file (glTF 2.0, FBX, Collada, X and whatever
// else libassimp reads): its meshes merged into one skin in the file's default pose, the file's
// own skinning weights, and its node hierarchy with one clip sampled as a Motion in BVH
// conventions, so that everything a BVH character does (retiming, mirroring, dressing, fitting)
// works on it unchanged.
//
// The Motion's rest pose (every channel zero) is the file's default pose: a joint's frame is
// turned so that it is aligned with the world there (as a BVH skeleton's frames are in its
// T-pose), which moves no joint and no vertex. Uniform node scales (an FBX armature's 100, a
// unit conversion) are taken into the skin's joint-local positions; a clip that changes a scale,
// or a non-uniform or mirroring scale on the skeleton, is an error.
#pragma once
#include <string>
#include <vector>

#include "core/mesh_build.hpp"
#include "scene/body.hpp"
#include "scene/model_file.hpp"
#include "scene/skeleton.hpp"

namespace vdc {

struct RiggedModel {
  Motion motion;    // the clip (a single frame of the default pose when the file has none)
  MeshSource skin;  // in the default pose, metres, y up; positions shared by faces are one
  std::vector<std::vector<SkinWeight>> weights;  // per skin position, summing to 1
  std::vector<std::string> clips;                // every clip's name, in the file's order
  std::vector<std::string> notes;                // what was left out or repaired, for the log
};

// Reads the file: units to metres and the up axis to +y from what the file states (FBX's
// UnitScaleFactor and UpAxis; Collada's are applied by the importer; glTF is metres, y up).
// Throws InputError(path, place, problem) for a file the importer cannot read, a clip it does
// not have, a skin vertex with no weight, a scale the skeleton cannot keep, no triangles.
RiggedModel read_rigged_model(const std::string& path, const ClipChoice& clip = {});

}  // namespace vdc
