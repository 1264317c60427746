// What `vdcloth report` puts in its page from a run's directory: the run's record (summary.json,
// stats.csv as columns, camera.json, vdcloth check's table, log.txt) and its frames' meshes, as
// scripts the page loads from disk (a browser reads no local file but a script without a server).
#pragma once
#include <map>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "output/run_output.hpp"

namespace vdc {

// The run in `run_dir` as the page reads it: "label" (the directory as given), "summary",
// "stats" (each stats.csv column as an array of numbers, null for nan or inf), "camera" (or null), "check" (status and
// rows of vdcloth check, or null), "log" (log.txt's lines, or null). Throws InputError naming the
// file, the place and the problem when summary.json or stats.csv is missing or malformed.
nlohmann::json read_run_record(const std::string& run_dir);

// The meshes of one frame as the script `vdcloth.addFrame(run, frame, meshes)`: per mesh its
// name, whether it is cloth, its positions (float32) and triangles (uint32) as little-endian
// base64, and a cloth's view factor per face (float32) and what set it (uint8, "reason") when
// its PLY has them. An obstacle whose
// triangles are those recorded in `topology` (by mesh name, from the first frame written) gets
// null triangles; the first frame of each obstacle records them. Throws InputError naming a mesh
// file that cannot be read.
void write_frame_script(std::ostream& out, int run_index, int frame, const FrameFiles& files, nlohmann::json& topology);

// Standard base64 (RFC 4648) of `bytes`.
std::string base64(const std::string& bytes);

}  // namespace vdc
