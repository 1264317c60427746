// `vdcloth run` as its stages: prepare the cluster and the groups (run_setup), open or resume
// the output, step the frames with progress (run_frame), finish or fail.
#include "app/run_command.hpp"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>

#include "app/cli.hpp"
#include "app/run_failure.hpp"
#include "app/run_frame.hpp"
#include "app/run_log.hpp"
#include "app/run_setup.hpp"
#include "dist/cluster.hpp"
#include "dist/last_words.hpp"
#include "dist/process_tables.hpp"
#include "output/camera_export.hpp"
#include "output/checkpoint.hpp"
#include "output/run_output.hpp"
#include "core/stopwatch.hpp"

namespace vdc {

namespace {

std::string format_duration(double s) {
  std::ostringstream o;
  int total = static_cast<int>(s + 0.5);
  if (total >= 3600) o << total / 3600 << "h" << std::setw(2) << std::setfill('0') << (total / 60) % 60 << "m";
  else if (total >= 60) o << total / 60 << "m" << std::setw(2) << std::setfill('0') << total % 60 << "s";
  else o << total << "s";
  return o.str();
}

// One build on every process: another may simulate differently.
bool same_build_everywhere(const Cluster& cluster, uint64_t build_hash, std::ostream& err) {
  if (cluster.size() == 1) return true;
  const std::vector<std::string> builds = cluster.all_gather(std::to_string(build_hash));
  for (const std::string& b : builds)
    if (b != builds.front()) {
      if (cluster.root()) err << "vdcloth: the processes of the run are not the same build of vdcloth" << std::endl;
      return false;
    }
  return true;
}

// The run's directory and tables: rank 0 sets the directory up (removing an earlier run's
// files) before any process writes; the others join it.
struct RunFiles {
  std::optional<RunOutput> output;
  std::optional<FrameTable> ranks;   // rank 0's, in a run of several processes
  std::optional<FrameTable> groups;  // rank 0's, in a run of several processes or garment groups
};

void open_files(const Cluster& cluster, const RunSetup& setup, RunFiles& files) {
  const std::optional<Checkpoint>& resume = setup.resume;
  if (!cluster.root()) files.output.emplace(RunOutput::joining(setup.dir));
  else if (resume) files.output.emplace(setup.dir, resume->frame);
  else files.output.emplace(setup.dir);
  if (!cluster.root()) return;
  const int kept = resume ? resume->frame : 0;
  if (cluster.size() > 1) files.ranks.emplace(setup.dir + "/ranks.csv", kRanksHeader, kept);
  if (cluster.size() > 1 || setup.owner.size() > 1) files.groups.emplace(setup.dir + "/groups.csv", kGroupsHeader, kept);
}

int faces_everywhere(const Cluster& cluster, const Ensemble& sim) {
  if (cluster.size() == 1) return sim.num_faces();
  int faces = 0;
  for (const std::string& f : cluster.all_gather(std::to_string(sim.num_faces()))) faces += std::stoi(f);
  return faces;
}

// The first line: what runs, how, and where it goes.
void announce(const RunArgs& args, const RunSetup& setup, int processes, int faces, int first, int preroll_frames, std::ostream& say) {
  const Ensemble& sim = *setup.sim;
  say << "vdcloth: " << sim.name() << ", " << setup.frames << " frames, mode " << sim_mode_name(args.mode) << ", " << setup.threads
      << " thread(s)" << (processes > 1 ? " on each of " + std::to_string(processes) + " processes" : "") << ", " << faces
      << " faces, output " << setup.dir;
  if (args.perturbation.gravity != 0) say << ", gravity perturbed by " << number_text(args.perturbation.gravity);
  if (args.perturbation.resolution != 0) say << ", resolution perturbed by " << number_text(args.perturbation.resolution);
  if (setup.resume) say << ", resumed at frame " << first;
  if (preroll_frames > 0) say << ", " << preroll_frames << " frames of pre-roll first";
  if (first < setup.settle_frames)
    say << ", sized as in adaptive mode up to frame " << setup.settle_frames << " (view.settle: the drape forms first)";
  say << std::endl;
}

// The frames of the run, from the pre-roll to the last, and how the run ends: done, or stopped
// part-way with what it got.
class FrameLoop {
 public:
  FrameLoop(const RunArgs& args, const Cluster& cluster, const RunSetup& setup, RunOutput& output, RunLog& log, FrameExchange& frames,
            std::optional<LastWords>& last_words, int first, std::chrono::steady_clock::time_point t0)
      : args_(args), cluster_(cluster), setup_(setup), output_(output), log_(log), frames_(frames), last_words_(last_words),
        first_(first), done_(first), t0_(t0) {}

  int run() {
    try {
      leave_last_words();
      write_camera();
      if (const std::optional<Failure> f = preroll()) return stop_part_way(*f);
      if (const std::optional<Failure> f = shot()) return stop_part_way(*f);
      frames_.finish_tables(done_);
    } catch (...) {
      // Outside the frames' exchange (rank 0's own files, a move): the other processes would
      // wait for this one forever, so the run ends as a whole.
      const int status = stop_part_way(failure_of(std::current_exception()));
      if (cluster_.size() > 1) cluster_.abort(status);
      return status;
    }
    return finish();
  }

 private:
  void write_camera() {
    const Scene& scene = setup_.sim->group_scene(0);
    if (!cluster_.root()) return;
    remove_camera_files(setup_.dir);  // of an earlier run, of another scene perhaps
    for (std::size_t c = 0; c < scene.cameras.size(); ++c)
      write_camera_files(scene.cameras[c].path, scene.frame_time, setup_.frames, setup_.dir, scene.cameras[c].name, static_cast<int>(c));
  }

  // Before the shot, characters move from the pose their garments were made in into the shot's
  // first pose; nothing of it is written (Scene::preroll_frames).
  std::optional<Failure> preroll() {
    if (setup_.resume) return std::nullopt;
    while (setup_.sim->frame() < 0) {
      const FrameOutcome f = frames_.step(false);
      if (f.failure.status != kExitOk) return f.failure;
      std::ostringstream line;
      line << "pre-roll frame " << f.stats.frame << "  " << std::fixed << std::setprecision(3) << f.stats.seconds << " s/frame  "
           << f.stats.faces << " faces";
      log_.progress(line.str());
    }
    return std::nullopt;
  }

  std::optional<Failure> shot() {
    while (done_ < setup_.frames) {
      const FrameOutcome f = frames_.step(true);
      if (f.failure.status != kExitOk) return f.failure;
      done_ = f.stats.frame;
      leave_last_words();
      const double left = seconds_since(t0_) / (done_ - first_) * (setup_.frames - done_);
      std::ostringstream line;
      line << "frame " << done_ << " of " << setup_.frames << "  " << std::fixed << std::setprecision(3) << f.stats.seconds
           << " s/frame  " << f.stats.faces << " faces  " << format_duration(left) << " left";
      log_.progress(line.str());
    }
    return std::nullopt;
  }

  void leave_last_words() {
    if (last_words_ && cluster_.root())
      last_words_->leave(setup_.dir + "/summary.json", frames_.summary("failed", "", done_), setup_.dir + "/" + kLogFile,
                         " (frames 0 to " + std::to_string(done_) + " are in " + setup_.dir + ")");
  }

  // A run that cannot go on says why and how far it got, in summary.json (if it can still be
  // written) and on the error stream.
  int stop_part_way(const Failure& f) {
    log_.end_line();
    if (!cluster_.root()) return kExitSimulationFailed;
    frames_.finish_checkpoints();
    try {
      output_.write_summary(frames_.summary("failed", f.line(), done_));
    } catch (const std::exception&) {  // the error stream still says why
    }
    log_.error(f.line() + " (frames 0 to " + std::to_string(done_) + " are in " + setup_.dir + ")");
    output_.append_log(f.line() + " (at frame " + std::to_string(done_) + ")");
    return kExitSimulationFailed;
  }

  int finish() {
    log_.end_line();
    if (!cluster_.root()) return kExitOk;
    frames_.finish_checkpoints();
    output_.write_summary(frames_.summary("done", "", done_));
    const double seconds = seconds_since(t0_);
    const std::string& dir = setup_.dir;
    std::ostream& out = log_.say();
    out << "vdcloth: done, " << done_ - first_ << " frames in " << format_duration(seconds) << " (" << std::fixed << std::setprecision(3)
        << seconds / std::max(done_ - first_, 1) << " s/frame); results in " << dir << std::endl;
    out << "vdcloth: to see it in a browser: vdcloth report " << dir << " writes " << dir << "/report/index.html\n";
    if (args_.mesh_every > 0 && !setup_.sim->group_scene(0).cameras.empty())
      out << "vdcloth: to look at it: vdcloth render " << args_.scene << " " << dir << " draws it through the shot camera into " << dir
          << "/render/ (add --video for an MP4, --colour view --wireframe for the mesh); " << dir << "/frames/ holds the OBJ and PLY meshes, "
          << camera_file(dir, setup_.sim->group_scene(0).cameras.front().name, ".chan") << " the camera\n";
    return kExitOk;
  }

  const RunArgs& args_;
  const Cluster& cluster_;
  const RunSetup& setup_;
  RunOutput& output_;
  RunLog& log_;
  FrameExchange& frames_;
  std::optional<LastWords>& last_words_;
  const int first_;
  int done_;
  const std::chrono::steady_clock::time_point t0_;  // the run's start, after the setup
};

}  // namespace

int run_command(const RunArgs& args, std::ostream& out, std::ostream& err, bool interactive) {
  // Under mpirun: the stop signals are blocked before MPI and OpenMP start their threads.
  std::optional<LastWords> last_words;
  if (started_by_mpi_launcher()) last_words.emplace();
  Cluster cluster;
  const CpuTicks ticks_at_start = machine_ticks();
  RunLog log(out, err, cluster.root(), interactive);
  RunSetup setup;
  if (const auto status = together(cluster, err, [&] { set_up_run(args, cluster, log.sink(), setup); })) return *status;
  if (!same_build_everywhere(cluster, setup.progress.build_hash, err)) return kExitBadInput;
  if (setup.nothing_to_do) {
    log.say() << "vdcloth: the run in " << setup.dir << " is done (" << setup.frames << " frames); nothing to resume" << std::endl;
    return kExitOk;
  }
  RunFiles files;
  if (const auto status = together(cluster, err, [&] { open_files(cluster, setup, files); })) return *status;
  log.attach(*files.output, cluster.root() && setup.resume ? "resumed at frame " + std::to_string(setup.resume->frame) : "");
  const Ensemble& sim = *setup.sim;
  const int processes = cluster.size();
  if (cluster.root() && processes > sim.groups())
    log.warn(std::to_string(processes) + " processes for " + std::to_string(sim.groups()) + " garment groups: processes " +
             std::to_string(sim.groups()) + " to " + std::to_string(processes - 1) + " have nothing to do");
  const int faces = faces_everywhere(cluster, sim);
  const bool prerolls = !setup.resume && sim.frame() < 0;
  const int first = prerolls ? 0 : sim.frame();
  announce(args, setup, processes, faces, first, prerolls ? -sim.frame() : 0, log.say());
  const auto t0 = std::chrono::steady_clock::now();
  FrameExchange frames(args, cluster, setup, *files.output, log,
                       [&] { return process_usage(setup.before, ticks_at_start, seconds_since(t0)); }, std::move(files.ranks),
                       std::move(files.groups));
  return FrameLoop(args, cluster, setup, *files.output, log, frames, last_words, first, t0).run();
}

}  // namespace vdc
