#include "app/run_args.hpp"

#include <sstream>

#include "app/cli.hpp"

namespace vdc {

extern const char* const kRunHelp =
    "usage: vdcloth run SCENE.json [--mode fixed|adaptive|view] [--frames N] [--out DIR] [--threads N]\n"
    "                  [--mesh-every N] [--checkpoint-every N] [--resume] [--group NAME]... [--perturb E]\n"
    "                  [--perturb-resolution E] [--force-moves]\n"
    "\n"
    "Simulates SCENE.json and writes DIR/stats.csv (one row a frame), DIR/frames/ (one OBJ per garment\n"
    "and obstacle per frame: cloth_<name>.<frame>.obj, obstacle_<name>.<frame>.obj, frame 0000 is the\n"
    "initial state; coordinates in metres to the micrometre; in view mode also a PLY of each garment's\n"
    "view factors), DIR/summary.json and, when the scene has a camera, DIR/camera.json and\n"
    "DIR/camera.chan (the shot camera at every frame, for compositing and 3D packages).\n"
    "\n"
    "options:\n"
    "  --mode M      fixed (non-adaptive mesh), adaptive (remeshed every frame) or view (adaptive,\n"
    "                resolution bent to the scene's camera). Default: fixed.\n"
    "  --frames N    number of frames to simulate (default: the scene's `frames`)\n"
    "  --out DIR     output directory (default: out/<scene name>)\n"
    "  --threads N   worker threads, 1 to 256 (default: all cores)\n"
    "  --mesh-every N  write the meshes of frames 0, N, 2N, ... only; 0: none (default: 1, every frame)\n"
    "  --checkpoint-every N  keep DIR/checkpoint.bin at frames N, 2N, ... and the last; 0: none\n"
    "                (default: 10)\n"
    "  --resume      go on with the run in DIR from its checkpoint, as if it had never stopped: same\n"
    "                scene file, mode and perturbation; --frames may give a later end than the\n"
    "                first run's\n"
    "  --group NAME  simulate only this garment group (repeatable): its garments, its obstacles and\n"
    "                those of no group. Groups are simulated apart, so each comes out as in the\n"
    "                whole scene: one character of a crowd, or a crowd run in shares\n"
    "  --perturb E   gravity times (1 + E), |E| at most 1e-3 (default: 0): with 1e-6, a run that\n"
    "                differs from the unperturbed one only by the growth of a perturbation below any\n"
    "                physical meaning, the chaos floor's reference for `vdcloth fidelity --floor`\n"
    "  --perturb-resolution E  adaptive and view modes: the remesher lets every edge be 1 + E times as\n"
    "                long as its criteria ask, |E| at most 0.1 (default: 0): a mesh the adaptive\n"
    "                method could as well have made (whether it collapses an edge already depends on\n"
    "                history across 20% of squared length); as `vdcloth fidelity --floor`, how far\n"
    "                a change of resolution alone moves the shot\n"
    "  --force-moves for tests of the MPI run: every group moves to the next process wherever\n"
    "                groups may move (after every frame; only at checkpoints with an iterative\n"
    "                linear solver)\n"
    "  --help        this text\n"
    "\n"
    "Under an MPI launcher (mpirun -np N vdcloth run ...), N processes share the scene's garment\n"
    "groups, each with its own --threads, and write the same results as one process would: every\n"
    "frame file, stats.csv but its timings and the checkpoints byte for byte. Groups start on the\n"
    "processes by their size and move between them at checkpoints when the measured costs say it\n"
    "pays; DIR/ranks.csv gives each process's busy and waiting seconds a frame, DIR/groups.csv each\n"
    "group's process and seconds. DIR must be on a\n"
    "file system every process sees (README.md, \"Crowds across machines\").\n";

namespace {

// --perturb's bound: a thousandth of gravity is still far below what a scene's author would
// notice, and a larger change is a different scene, not a perturbation.
constexpr double kMaxPerturbation = 1e-3;
// --perturb-resolution's bound: a tenth of every edge's length is about the remesher's own
// hysteresis (remesher.hpp, collapse_margin 0.2 of the squared length); beyond it, another
// resolution.
constexpr double kMaxResolutionPerturbation = 0.1;

}  // namespace

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

RunArgs parse_run_args(const std::vector<std::string>& args) {
  RunArgs r;
  for (ArgumentReader in(args, 1); !in.done();) {
    const std::string& a = in.next();
    if (a == "--mode") {
      const std::string& m = in.value();
      if (!parse_sim_mode(m, r.mode)) throw UsageError("--mode expects fixed, adaptive or view, got '" + m + "'");
    } else if (a == "--frames") {
      r.frames = parse_positive_int(a, in.value());
    } else if (a == "--out") {
      r.out = in.value();
      if (r.out.empty()) throw UsageError("--out needs a directory");
    } else if (a == "--threads") {
      r.threads = parse_int_in(a, in.value(), 1, kMaxThreads);
    } else if (a == "--mesh-every") {
      r.mesh_every = parse_int_in(a, in.value(), 0, 1'000'000);
    } else if (a == "--checkpoint-every") {
      r.checkpoint_every = parse_int_in(a, in.value(), 0, 1'000'000);
    } else if (a == "--resume") {
      r.resume = true;
    } else if (a == "--group") {
      r.groups.push_back(in.value());
    } else if (a == "--perturb") {
      r.perturbation.gravity = parse_number(a, in.value(), -kMaxPerturbation, kMaxPerturbation);
    } else if (a == "--force-moves") {
      r.force_moves = true;
    } else if (a == "--perturb-resolution") {
      r.perturbation.resolution = parse_number(a, in.value(), -kMaxResolutionPerturbation, kMaxResolutionPerturbation);
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "'");
    } else if (r.scene.empty()) {
      r.scene = a;
    } else {
      throw UsageError("only one scene file, got '" + r.scene + "' and '" + a + "'");
    }
  }
  if (r.scene.empty()) throw UsageError("run needs a scene file");
  return r;
}

}  // namespace vdc
