// Obstacles animated by a sequence of OBJ files, one a frame, all with the topology of the first:
// positions are interpolated linearly between frames (so velocities are the sequence's finite
// differences) and held at the last frame after the sequence ends.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.hpp"
#include "core/surface_repair.hpp"

namespace vdc {

struct ObjSequence {
  Mesh mesh;                             // the first file's mesh (topology and first positions), repaired for collisions
  std::string repairs;                   // what its repair found (SurfaceRepairs::summary), "" for nothing
  std::vector<std::vector<Vec3>> frames; // positions per file, by node index
  double frame_time = 0.04;              // s between files
};

// Positions at time t of frames spaced frame_time apart: linear between frames, the first
// before 0 and the last after the end.
std::vector<Vec3> interpolate_frames(const std::vector<std::vector<Vec3>>& frames, double frame_time, double t);

// The file names of a printf-style pattern with one integer field (`body.%04d.obj`) for
// first, first + 1, ..., first + count - 1.
std::vector<std::string> sequence_files(const std::string& pattern, int first, int count);

// Reads the files; throws InputError naming the file and the problem (unreadable, malformed,
// or a vertex count or face list that differs from the first file's).
ObjSequence load_obj_sequence(const std::vector<std::string>& files, double frame_time);

}  // namespace vdc
