// A run's checkpoint, RUN/checkpoint.bin: everything `vdcloth run --resume` needs to go on from
// the frame it was written at as the run itself would have (every part's garment meshes, array
// for array), plus the mode, a hash of the scene file and the run's costs so far.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/resource_usage.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";

struct Checkpoint {
  uint64_t scene_hash = 0;  // file_hash of the scene file the run was made from
  std::string mode;         // sim_mode_name
  int frame = 0;
  int segments = 1;         // processes the run has been made in, this one included
  ResourceUsage usage;      // of those processes up to this frame
  std::vector<ResumePoint> parts;  // one per garment group, in the ensemble's order
};

// FNV-1a of a file's bytes. Throws InputError when it cannot be read.
uint64_t file_hash(const std::string& path);

// Writes the checkpoint of `run` at its current frame to `path`, through a temporary file
// renamed into place, so a run stopped while writing keeps its previous checkpoint.
void write_checkpoint(const std::string& path, const Ensemble& run, uint64_t scene_hash, int segments, const ResourceUsage& usage);

// Reads a checkpoint; throws InputError naming the file (and the byte) when it is missing,
// damaged or not a checkpoint.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace vdc
