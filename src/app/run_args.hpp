// `vdcloth run`'s command line: its help, its options and their parsing.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace vdc {

extern const char* const kRunHelp;

struct RunArgs {
  std::string scene;
  SimMode mode = SimMode::Fixed;
  std::optional<int> frames;
  std::string out;
  int threads = 0;
  int mesh_every = 1;  // write meshes at frames that are multiples of this; 0: none
  int checkpoint_every = 10;  // checkpoint at frames that are multiples of this, and the last; 0: none
  bool resume = false;
  std::vector<std::string> groups;  // --group: simulate only these garment groups
  Perturbation perturbation;  // --perturb and --perturb-resolution
  bool force_moves = false;  // --force-moves: every group to the next process wherever groups may move
};

// args[0] is "run". Throws UsageError.
RunArgs parse_run_args(const std::vector<std::string>& args);

// A number as the user would write it (1e-06).
std::string number_text(double x);

}  // namespace vdc
