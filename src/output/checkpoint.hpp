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

// One group's part of a checkpoint (its garments' names and meshes now), as bytes: a run made by
// several processes gathers each group's from the process stepping it, and hands a group over
// to another process in the same form.
std::string checkpoint_part(const Simulation& part);
// A part's bytes read back as where the group resumes at `frame`; throws InputError naming
// `source` when they are not a part.
ResumePoint read_checkpoint_part(const std::string& bytes, int frame, const std::string& source);

// Writes `c` (but its parts) with the mode and frame given and the groups' `parts`
// (checkpoint_part, in group order) to `path`, through a temporary file flushed to disk and
// renamed into place, so a run stopped while writing keeps its previous checkpoint. Throws
// OutputError, leaving no temporary file, when it cannot.
void write_checkpoint(const std::string& path, const Checkpoint& c, SimMode mode, int frame, const std::vector<std::string>& parts);
// The same with the parts of `run` (every group here), at its current frame.
void write_checkpoint(const std::string& path, const Ensemble& run, const Checkpoint& c);

// Reads a checkpoint; throws InputError naming the file (and the byte) when it is missing,
// damaged or not a checkpoint.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace vdc
