#include "app/run_setup.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <thread>

#include "app/cli.hpp"
#include "core/stopwatch.hpp"
#include "core/error.hpp"
#include "dist/placement.hpp"
#include "output/run_output.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

// The scene as the command line asks for it: its groups, its length, its perturbation.
Scene read_scene(const RunArgs& args) {
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
  return scene;
}

void take_settings(const RunArgs& args, const Scene& scene, int processes, RunSetup& setup) {
  setup.threads = args.threads > 0 ? args.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  setup.dir = args.out.empty() ? "out/" + scene.name : args.out;
  setup.frames = scene.frames;
  if (args.mode == SimMode::View) setup.settle_frames = scene.view.settle_frames(scene.frame_time);
  setup.progress.checkpoint_every = args.checkpoint_every;
  setup.progress.perturbation = args.perturbation;
  if (args.checkpoint_every > 0 || args.resume || processes > 1) {
    setup.progress.scene_hash = file_hash(args.scene);
    setup.progress.build_hash = executable_hash();
  }
}

// The checkpoint to go on from, when resuming; whether the run is already done.
void find_resume_point(const RunArgs& args, RunSetup& setup) {
  if (!args.resume) return;
  setup.resume = checkpoint_to_resume(args, setup.dir, setup.progress.build_hash);
  if (setup.resume->frame > setup.frames)
    throw UsageError("--resume: the run in " + setup.dir + " is at frame " + std::to_string(setup.resume->frame) + ", past the " +
                     std::to_string(setup.frames) + " frames asked for");
  if (setup.resume->frame == setup.frames && run_is_done(setup.dir, setup.frames))  // its summary stays as it is
    setup.nothing_to_do = true;
}

// Groups start on the processes by their garments' faces (at the checkpoint's frame when
// resumed), the largest first. Returns the groups of process `rank`.
std::vector<int> place_groups(const Scene& scene, const Cluster& cluster, RunSetup& setup) {
  std::vector<double> cost;
  if (setup.resume)
    for (const ResumePoint& p : setup.resume->parts) {
      double faces = 0;
      for (const Mesh& m : p.garments) faces += m.num_faces();
      cost.push_back(faces);
    }
  else
    cost = group_faces(scene);
  setup.owner = place_longest_first(cost, cluster.size());
  std::vector<int> here;
  for (std::size_t g = 0; g < setup.owner.size(); ++g)
    if (setup.owner[g] == cluster.rank()) here.push_back(static_cast<int>(g));
  return here;
}

void build_groups(const RunArgs& args, Scene scene, const Cluster& cluster, std::vector<int> here, const Simulation::Log& log,
                  RunSetup& setup) {
  const SimOptions options{args.mode, setup.threads};
  std::optional<Checkpoint>& resume = setup.resume;
  setup.segments = resume ? resume->segments + 1 : 1;
  setup.progress.segments = setup.segments;
  setup.before = resume ? resume->usage : ResourceUsage{};
  const auto built = std::chrono::steady_clock::now();
  std::optional<std::vector<int>> share;
  if (cluster.size() > 1) share = std::move(here);
  if (resume)
    setup.sim.emplace(std::move(scene), options, log, std::move(resume->parts), setup.dir + "/" + kCheckpointFile, share);
  else
    setup.sim.emplace(std::move(scene), options, log, share);
  if (setup.sim->num_faces() > 0) setup.rebuild_seconds_per_face = seconds_since(built) / setup.sim->num_faces();
}

}  // namespace

void set_up_run(const RunArgs& args, const Cluster& cluster, const Simulation::Log& log, RunSetup& setup) {
  Scene scene = read_scene(args);
  if (cluster.root()) {  // what reading an artist's files repaired, once (a crowd's copies share it)
    std::set<std::string> said;
    for (const ObstacleSpec& o : scene.obstacles)
      for (const std::string& note : o.notes)
        if (said.insert(note).second) log(note);
  }
  take_settings(args, scene, cluster.size(), setup);
  find_resume_point(args, setup);
  if (setup.nothing_to_do) return;
  std::vector<int> here = place_groups(scene, cluster, setup);
  build_groups(args, std::move(scene), cluster, std::move(here), log, setup);
}

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

}  // namespace vdc
