// A run's checkpoint, RUN/checkpoint.bin: everything `vdcloth run --resume` needs to go on from
// the frame it was written at as the run itself would have (every part's garment meshes, array
// for array), plus the mode, the perturbation, a hash of the scene file and the run's costs so far.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/resource_usage.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";

struct Checkpoint {
  uint64_t scene_hash = 0;  // file_hash of the scene file the run was made from
  uint64_t build_hash = 0;  // executable_hash of the vdcloth that wrote it
  int checkpoint_every = 0; // the run's interval: the solvers restart at each checkpoint
  Perturbation perturbation;  // vdcloth run --perturb and --perturb-resolution
  std::string mode;         // sim_mode_name
  int frame = 0;
  int segments = 1;         // processes the run has been made in, this one included
  ResourceUsage usage;      // of those processes up to this frame
  std::vector<ResumePoint> parts;  // one per garment group, in the ensemble's order
};

// FNV-1a of a file's bytes. Throws InputError when it cannot be read.
uint64_t file_hash(const std::string& path);
// file_hash of this program (/proc/self/exe): another build may simulate differently.
uint64_t executable_hash();

// Writes `c` (but its parts: those come from `run`, at its current frame) to `path`, through a
// temporary file flushed to disk and renamed into place, so a run stopped while writing keeps
// its previous checkpoint. Throws InputError, leaving no temporary file, when it cannot.
void write_checkpoint(const std::string& path, const Ensemble& run, const Checkpoint& c);

// Reads a checkpoint; throws InputError naming the file (and the byte) when it is missing,
// damaged or not a checkpoint.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace vdc
