#include "app/cli.hpp"

#include "app/check_command.hpp"
#include "app/fidelity_command.hpp"
#include "app/render_command.hpp"
#include "app/report_command.hpp"
#include "app/table1.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <new>
#include <optional>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "output/camera_export.hpp"
#include "output/checkpoint.hpp"
#include "output/run_output.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

const char* kMainHelp =
    "vdcloth: view-dependent adaptive cloth simulation\n"
    "\n"
    "usage:\n"
    "  vdcloth run SCENE.json [options]   simulate a scene\n"
    "  vdcloth bench table1 [options]     Koh et al. 2014's Table 1 on the project's scenes\n"
    "  vdcloth render SCENE.json RUN_DIR  pictures of a run through the scene's camera; with\n"
    "                 [options]           --compare, two runs side by side and their differences\n"
    "  vdcloth fidelity SCENE.json RUN_DIR REFERENCE_DIR [options]\n"
    "                                     how like a reference run a run looks through the scene's\n"
    "                                     camera (silhouette overlap, wrinkle detail, popping),\n"
    "                                     judged shot by shot against the chaos floor\n"
    "  vdcloth report RUN_DIR [options]   a page to open in a browser: the run in 3D with a timeline,\n"
    "                                     its faces and seconds per frame plotted, its summary\n"
    "  vdcloth check RUN_DIR [--every N]  no garment crosses itself, another or a body at any\n"
    "                                     written frame (exact triangle tests)\n"
    "  vdcloth --help                     this text\n"
    "  vdcloth --version                  version\n"
    "\n"
    "`vdcloth COMMAND --help` lists a command's options. Exit status: 0 done, 2 bad input or usage,\n"
    "3 a failure part-way: a simulation that could not be recovered, results that could not be written,\n"
    "memory that ran out or an unexpected error (check: a crossing; fidelity: a failed verdict).\n";

const char* kBenchHelp =
    "usage: vdcloth bench table1 [options]\n"
    "\n"
    "Benchmarks made of whole runs. There is one: table1, Koh, Narain and O'Brien's Table 1 on the\n"
    "project's scenes (fixed, adaptive and view runs of karate, solo-dancer and dancers-10; faces\n"
    "and seconds per frame, speed-ups). `vdcloth bench table1 --help` gives its options. The\n"
    "micro-benchmarks of the build (build/bench/vdcloth_bench) are Google Benchmark's.\n";

const char* kRunHelp =
    "usage: vdcloth run SCENE.json [--mode fixed|adaptive|view] [--frames N] [--out DIR] [--threads N]\n"
    "                  [--mesh-every N] [--checkpoint-every N] [--resume] [--group NAME]... [--perturb E]\n"
    "                  [--perturb-resolution E]\n"
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
    "  --help        this text\n";

// --perturb's bound: a thousandth of gravity is still far below what a scene's author would
// notice, and a larger change is a different scene, not a perturbation.
constexpr double kMaxPerturbation = 1e-3;
// --perturb-resolution's bound: a tenth of every edge's length is about the remesher's own
// hysteresis (remesher.hpp, collapse_margin 0.2 of the squared length); beyond it, another
// resolution.
constexpr double kMaxResolutionPerturbation = 0.1;

// A number as the user would write it (1e-06).
std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

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
};

}  // namespace

int parse_int_in(const std::string& option, const std::string& value, int lowest, int highest) {
  std::size_t used = 0;
  long long n = 0;
  try {
    n = std::stoll(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty() || n < lowest || n > highest)
    throw UsageError(option + " expects a whole number from " + std::to_string(lowest) + " to " + std::to_string(highest) + ", got '" +
                     value + "'");
  return static_cast<int>(n);
}

int parse_positive_int(const std::string& option, const std::string& value) { return parse_int_in(option, value, 1, 1'000'000); }

double parse_number(const std::string& option, const std::string& value, double lowest, double highest) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty() || !(x >= lowest && x <= highest)) {
    std::ostringstream range;
    range << lowest << " to " << highest;
    throw UsageError(option + " expects a number from " + range.str() + ", got '" + value + "'");
  }
  return x;
}

namespace {

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

std::string format_duration(double s) {
  std::ostringstream o;
  int total = static_cast<int>(s + 0.5);
  if (total >= 3600) o << total / 3600 << "h" << std::setw(2) << std::setfill('0') << (total / 60) % 60 << "m";
  else if (total >= 60) o << total / 60 << "m" << std::setw(2) << std::setfill('0') << total % 60 << "s";
  else o << total << "s";
  return o.str();
}

// The checkpoint of the run in `dir` to resume, checked against the scene file, this build,
// the mode and the checkpoint interval: anything else would make another run than the one
// stopped.
Checkpoint checkpoint_to_resume(const RunArgs& args, const std::string& dir, uint64_t build_hash) {
  const std::string path = dir + "/" + kCheckpointFile;
  if (std::error_code ec; !fs::is_regular_file(path, ec))
    throw InputError(path, "", "no checkpoint to resume from (the run was made with --checkpoint-every 0, or stopped before its first)");
  Checkpoint c = read_checkpoint(path);
  if (c.scene_hash != file_hash(args.scene))
    throw InputError(path, "", "made from another version of " + args.scene + ": run without --resume to start again");
  if (c.build_hash != build_hash)
    throw InputError(path, "", "written by another build of vdcloth, which may simulate differently: run without --resume to start again");
  if (c.mode != sim_mode_name(args.mode))
    throw UsageError("--resume: the run in " + dir + " is in " + c.mode + " mode, not " + sim_mode_name(args.mode));
  if (c.perturbation.gravity != args.perturbation.gravity)
    throw UsageError("--resume: the run in " + dir + " was made with --perturb " + number_text(c.perturbation.gravity) + ", not " +
                     number_text(args.perturbation.gravity) + "; resume it with --perturb " + number_text(c.perturbation.gravity));
  if (c.perturbation.resolution != args.perturbation.resolution)
    throw UsageError("--resume: the run in " + dir + " was made with --perturb-resolution " + number_text(c.perturbation.resolution) +
                     ", not " + number_text(args.perturbation.resolution) + "; resume it with --perturb-resolution " +
                     number_text(c.perturbation.resolution));
  if (c.checkpoint_every != args.checkpoint_every)
    throw UsageError("--resume: the run in " + dir + " was checkpointed every " + std::to_string(c.checkpoint_every) +
                     " frames; resume it with --checkpoint-every " + std::to_string(c.checkpoint_every) +
                     " (the solvers restart at each checkpoint, so another interval makes another run)");
  return c;
}

int run_command(const RunArgs& args, std::ostream& out, std::ostream& err, bool interactive) {
  Scene scene = load_scene(args.scene);
  if (!args.groups.empty()) {
    try {
      scene = keep_groups(std::move(scene), args.groups);
    } catch (const std::invalid_argument& e) {
      throw UsageError("--group: " + args.scene + " has " + e.what());
    }
  }
  if (args.frames) scene.frames = *args.frames;
  apply_perturbation(scene, args.perturbation);
  const int threads = args.threads > 0 ? args.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const std::string dir = args.out.empty() ? "out/" + scene.name : args.out;
  const int frames = scene.frames;
  Checkpoint progress;  // what each checkpoint of this run records besides the meshes
  progress.checkpoint_every = args.checkpoint_every;
  progress.perturbation = args.perturbation;
  if (args.checkpoint_every > 0 || args.resume) {
    progress.scene_hash = file_hash(args.scene);
    progress.build_hash = executable_hash();
  }
  std::optional<Checkpoint> resume;
  if (args.resume) {
    resume = checkpoint_to_resume(args, dir, progress.build_hash);
    if (resume->frame > frames)
      throw UsageError("--resume: the run in " + dir + " is at frame " + std::to_string(resume->frame) + ", past the " +
                       std::to_string(frames) + " frames asked for");
    if (resume->frame == frames && run_is_done(dir, frames)) {  // its summary stays as it is
      out << "vdcloth: the run in " << dir << " is done (" << frames << " frames); nothing to resume" << std::endl;
      return kExitOk;
    }
  }

  bool line_open = false;
  // Warnings go to the error stream and to the run's log.txt, kept aside until the output
  // directory is set up (the run's setup may warn before it).
  std::optional<RunOutput> output;
  std::vector<std::string> early_log;
  auto log = [&](const std::string& msg) {
    if (line_open) out << "\n";
    line_open = false;
    err << "vdcloth: " << msg << std::endl;
    if (output) output->append_log(msg);
    else early_log.push_back(msg);
  };
  const SimOptions options{args.mode, threads};
  const int segments = resume ? resume->segments + 1 : 1;
  progress.segments = segments;
  const ResourceUsage before = resume ? resume->usage : ResourceUsage{};
  const CpuTicks ticks_at_start = machine_ticks();
  Ensemble sim = resume ? Ensemble(std::move(scene), options, log, std::move(resume->parts), dir + "/" + kCheckpointFile)
                        : Ensemble(std::move(scene), options, log);
  if (resume) output.emplace(dir, resume->frame);
  else output.emplace(dir);
  if (resume) output->append_log("resumed at frame " + std::to_string(resume->frame));
  for (const std::string& msg : early_log) output->append_log(msg);
  const bool prerolls = !resume && sim.frame() < 0;
  const int preroll_frames = prerolls ? -sim.frame() : 0;
  const int first = prerolls ? 0 : sim.frame();
  out << "vdcloth: " << sim.name() << ", " << frames << " frames, mode " << sim_mode_name(args.mode) << ", " << threads
      << " thread(s), " << sim.num_faces() << " faces, output " << dir;
  if (args.perturbation.gravity != 0) out << ", gravity perturbed by " << number_text(args.perturbation.gravity);
  if (args.perturbation.resolution != 0) out << ", resolution perturbed by " << number_text(args.perturbation.resolution);
  if (resume) out << ", resumed at frame " << first;
  if (prerolls) out << ", " << preroll_frames << " frames of pre-roll first";
  out << std::endl;

  auto t0 = std::chrono::steady_clock::now();
  auto usage = [&] {
    return process_usage(before, ticks_at_start, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  };
  int done = first;
  // A run that cannot go on says why and how far it got, in summary.json (if it can still be
  // written) and on the error stream.
  auto stop_part_way = [&](const std::string& what, const std::string& why) {
    if (line_open) out << "\n";
    try {
      output->write_summary(sim, "failed", what + ": " + why, usage(), segments, done, threads, args.perturbation);
    } catch (const std::exception&) {  // the error stream still says why
    }
    err << "vdcloth: " << what << ": " << why << " (frames 0 to " << done << " are in " << dir << ")" << std::endl;
    output->append_log(what + ": " + why + " (at frame " + std::to_string(done) + ")");
    return kExitSimulationFailed;
  };
  try {
    const Scene& shot = sim.parts().front()->scene();
    if (shot.camera) write_camera_files(*shot.camera, shot.frame_time, frames, dir);
    else remove_camera_files(dir);  // of an earlier run of another scene
    if (prerolls) {
      // Before the shot, characters move from the pose their garments were made in into the
      // shot's first pose; nothing of it is written (Scene::preroll_frames).
      while (sim.frame() < 0) {
        const FrameStats s = sim.step_frame();
        std::ostringstream line;
        line << "pre-roll frame " << s.frame << "  " << std::fixed << std::setprecision(3) << s.seconds << " s/frame  " << s.faces << " faces";
        if (interactive) {
          out << "\r" << line.str() << "   " << std::flush;
          line_open = true;
        } else {
          out << line.str() << "\n" << std::flush;
        }
      }
    }
    if (args.mesh_every > 0 && !resume) output->write_frame(sim, 0);
    while (done < frames) {
      FrameStats s = sim.step_frame();
      if (args.mesh_every > 0 && s.frame % args.mesh_every == 0) output->write_frame(sim, s.frame);
      output->write_stats_row(s);
      done = s.frame;
      if (args.checkpoint_every > 0 && (done % args.checkpoint_every == 0 || done == frames)) {
        sim.restart_solvers();
        progress.usage = usage();
        try {
          write_checkpoint(dir + "/" + kCheckpointFile, sim, progress);
        } catch (const OutputError& e) {
          log(std::string(e.what()) + "; the run goes on, resumable from its previous checkpoint");
        }
      }
      double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double left = elapsed / (done - first) * (frames - done);
      std::ostringstream line;
      line << "frame " << done << " of " << frames << "  " << std::fixed << std::setprecision(3) << s.seconds << " s/frame  "
           << s.faces << " faces  " << format_duration(left) << " left";
      if (interactive) {
        out << "\r" << line.str() << "   " << std::flush;
        line_open = true;
      } else {
        out << line.str() << "\n" << std::flush;
      }
    }
  } catch (const SimulationError& e) {
    return stop_part_way("simulation failed", e.what());
  } catch (const OutputError& e) {
    return stop_part_way("writing the results failed", e.what());
  } catch (const std::bad_alloc&) {
    return stop_part_way("out of memory", "an allocation failed");
  } catch (const std::exception& e) {  // a fault of vdcloth's own or of the system, not of the input
    return stop_part_way("unexpected error", e.what());
  }
  if (line_open) out << "\n";
  const ResourceUsage total = usage();
  output->write_summary(sim, "done", "", total, segments, done, threads, args.perturbation);
  const double this_segment = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out << "vdcloth: done, " << done - first << " frames in " << format_duration(this_segment) << " ("
      << std::fixed << std::setprecision(3) << this_segment / std::max(done - first, 1) << " s/frame); results in " << dir << std::endl;
  out << "vdcloth: to see it in a browser: vdcloth report " << dir << " writes " << dir << "/report/index.html\n";
  if (args.mesh_every > 0 && sim.parts().front()->scene().camera)
    out << "vdcloth: to look at it: vdcloth render " << args.scene << " " << dir << " draws it through the shot camera into "
        << dir << "/render/ (add --video for an MP4, --colour view --wireframe for the mesh); " << dir
        << "/frames/ holds the OBJ and PLY meshes, " << dir << "/camera.chan the camera\n";
  return kExitOk;
}

}  // namespace

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool interactive) {
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      (args.empty() ? err : out) << kMainHelp;
      return args.empty() ? kExitBadInput : kExitOk;
    }
    if (args[0] == "--version") {
      out << "vdcloth " << VDCLOTH_VERSION << "\n";
      return kExitOk;
    }
    if (args[0] == "bench") {
      if (args.size() >= 2 && (args[1] == "--help" || args[1] == "-h")) {
        out << kBenchHelp;
        return kExitOk;
      }
      if (args.size() < 2) throw UsageError("bench expects a benchmark name: table1");
      if (args[1] != "table1") throw UsageError("bench: unknown benchmark '" + args[1] + "' (there is table1)");
      return table1_command(std::vector<std::string>(args.begin() + 2, args.end()), out, err);
    }
    if (args[0] == "check") return check_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "render") return render_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "report") return report_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "fidelity") return fidelity_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] != "run") throw UsageError("unknown command '" + args[0] + "' (try vdcloth --help)");
    for (std::size_t i = 1; i < args.size(); ++i)
      if (args[i] == "--help" || args[i] == "-h") {
        out << kRunHelp;
        return kExitOk;
      }
    return run_command(parse_run_args(args), out, err, interactive);
  } catch (const UsageError& e) {
    err << "vdcloth: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InputError& e) {
    err << "vdcloth: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const SimulationError& e) {
    err << "vdcloth: simulation failed: " << e.what() << "\n";
    return kExitSimulationFailed;
  } catch (const OutputError& e) {
    err << "vdcloth: writing the results failed: " << e.what() << "\n";
    return kExitSimulationFailed;
  } catch (const std::bad_alloc&) {
    err << "vdcloth: out of memory: an allocation failed\n";
    return kExitSimulationFailed;
  } catch (const std::exception& e) {
    err << "vdcloth: unexpected error: " << e.what() << "\n";
    return kExitSimulationFailed;
  }
}

}  // namespace vdc
