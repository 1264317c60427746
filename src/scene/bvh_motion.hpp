// Reader of BVH motion files (Biovision hierarchy): the joint hierarchy with offsets and
// channels in any order, then the frames at any frame time. Errors name the file, the line and
// the problem.
#pragma once
#include <string>

#include "scene/skeleton.hpp"

namespace vdc {

// Throws InputError(path, "line L", problem) on a malformed file.
Motion read_bvh(const std::string& path);
// The same from text already read; `name` is used in errors.
Motion parse_bvh(const std::string& text, const std::string& name);
// Writes a motion as BVH (rotations in the channel orders of its skeleton). False on I/O failure.
bool write_bvh(const Motion& motion, const std::string& path);

}  // namespace vdc
