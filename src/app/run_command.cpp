#include "app/run_command.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <new>
#include <sstream>
#include <thread>

#include "app/cli.hpp"
#include "core/binary_io.hpp"
#include "core/error.hpp"
#include "dist/cluster.hpp"
#include "dist/frame_report.hpp"
#include "dist/last_words.hpp"
#include "dist/placement.hpp"
#include "dist/process_tables.hpp"
#include "output/camera_export.hpp"
#include "output/checkpoint.hpp"
#include "output/checkpoint_writer.hpp"
#include "output/run_output.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

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


// What failed, as run_cli says it: the exit status and the line after "vdcloth: ".
struct Failure {
  int status = kExitOk;
  std::string what, why;  // what: "simulation failed", ...; empty for bad input
  std::string line() const { return what.empty() ? why : what + ": " + why; }
};

Failure failure_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const UsageError& e) {
    return {kExitBadInput, "", e.what()};
  } catch (const InputError& e) {
    return {kExitBadInput, "", e.what()};
  } catch (const SimulationError& e) {
    return {kExitSimulationFailed, "simulation failed", e.what()};
  } catch (const OutputError& e) {
    return {kExitSimulationFailed, "writing the results failed", e.what()};
  } catch (const std::bad_alloc&) {
    return {kExitSimulationFailed, "out of memory", "an allocation failed"};
  } catch (const std::exception& e) {  // a fault of vdcloth's own or of the system, not of the input
    return {kExitSimulationFailed, "unexpected error", e.what()};
  }
}

// Runs `step` on every process of `cluster` and says whether all of them went through. One
// process: its exception goes on as it is. Several: each learns the others' outcome; when one
// failed, rank 0 says the first failure (with its rank) and every process returns its status.
template <class Step>
std::optional<int> together(const Cluster& cluster, std::ostream& err, Step&& step) {
  if (cluster.size() == 1) {
    step();
    return std::nullopt;
  }
  Failure mine;
  try {
    step();
  } catch (...) {
    mine = failure_of(std::current_exception());
  }
  BinaryWriter said;
  said.value<int32_t>(mine.status);
  said.string(mine.line());
  const std::vector<std::string> all = cluster.all_gather(said.bytes());
  for (std::size_t r = 0; r < all.size(); ++r) {
    BinaryReader in(all[r].data(), all[r].size());
    const int status = in.value<int32_t>();
    if (status == kExitOk) continue;
    const std::string line = in.string();
    if (cluster.root()) err << "vdcloth: " << (r > 0 ? "process " + std::to_string(r) + ": " : "") << line << std::endl;
    return status;
  }
  return std::nullopt;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int run_command(const RunArgs& args, std::ostream& out, std::ostream& err, bool interactive) {
  // Under mpirun: the stop signals are blocked before MPI and OpenMP start their threads.
  std::optional<LastWords> last_words;
  if (started_by_mpi_launcher()) last_words.emplace();
  Cluster cluster;
  const bool root = cluster.root();
  const int processes = cluster.size();
  std::ostringstream muted;
  std::ostream& say = root ? out : muted;  // progress and advice: rank 0's

  std::optional<Ensemble> sim;
  std::optional<RunOutput> output;
  std::optional<Checkpoint> resume;
  Checkpoint progress;  // what each checkpoint of this run records besides the meshes
  std::string dir;
  int frames = 0, threads = 1;
  double settle_frames = 0;  // view mode: frames from the shot's start left to the adaptive sizing
  bool nothing_to_do = false;
  std::vector<int> owner;  // the process stepping each group
  double rebuild_seconds_per_face = 0;
  bool line_open = false;
  // Warnings go to the error stream and to the run's log.txt, kept aside until the output
  // directory is set up (the run's setup may warn before it).
  std::vector<std::string> early_log;
  auto log = [&](const std::string& msg) {
    if (line_open) out << "\n";
    line_open = false;
    err << "vdcloth: " << msg << std::endl;
    if (output) output->append_log(msg);
    else early_log.push_back(msg);
  };
  int segments = 1;
  ResourceUsage before;
  const CpuTicks ticks_at_start = machine_ticks();

  // Every process reads the scene (and the checkpoint) and builds the groups it starts with.
  if (const auto status = together(cluster, err, [&] {
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
        threads = args.threads > 0 ? args.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
        dir = args.out.empty() ? "out/" + scene.name : args.out;
        frames = scene.frames;
        if (args.mode == SimMode::View) settle_frames = scene.view.settle_frames(scene.frame_time);
        progress.checkpoint_every = args.checkpoint_every;
        progress.perturbation = args.perturbation;
        if (args.checkpoint_every > 0 || args.resume || processes > 1) {
          progress.scene_hash = file_hash(args.scene);
          progress.build_hash = executable_hash();
        }
        if (args.resume) {
          resume = checkpoint_to_resume(args, dir, progress.build_hash);
          if (resume->frame > frames)
            throw UsageError("--resume: the run in " + dir + " is at frame " + std::to_string(resume->frame) + ", past the " +
                             std::to_string(frames) + " frames asked for");
          if (resume->frame == frames && run_is_done(dir, frames)) {  // its summary stays as it is
            nothing_to_do = true;
            return;
          }
        }
        // Groups start on the processes by their garments' faces (at the checkpoint's frame
        // when resumed), the largest first.
        std::vector<double> cost;
        if (resume)
          for (const ResumePoint& p : resume->parts) {
            double faces = 0;
            for (const Mesh& m : p.garments) faces += m.num_faces();
            cost.push_back(faces);
          }
        else
          cost = group_faces(scene);
        owner = place_longest_first(cost, processes);
        std::vector<int> here;
        for (std::size_t g = 0; g < owner.size(); ++g)
          if (owner[g] == cluster.rank()) here.push_back(static_cast<int>(g));
        const SimOptions options{args.mode, threads};
        segments = resume ? resume->segments + 1 : 1;
        progress.segments = segments;
        before = resume ? resume->usage : ResourceUsage{};
        const auto built = std::chrono::steady_clock::now();
        std::optional<std::vector<int>> share;
        if (processes > 1) share = here;
        if (resume) sim.emplace(std::move(scene), options, log, std::move(resume->parts), dir + "/" + kCheckpointFile, share);
        else sim.emplace(std::move(scene), options, log, share);
        if (sim->num_faces() > 0) rebuild_seconds_per_face = seconds_since(built) / sim->num_faces();
      }))
    return *status;
  if (processes > 1) {
    // One build on every process: another may simulate differently.
    const std::vector<std::string> builds = cluster.all_gather(std::to_string(progress.build_hash));
    for (const std::string& b : builds)
      if (b != builds.front()) {
        if (root) err << "vdcloth: the processes of the run are not the same build of vdcloth" << std::endl;
        return kExitBadInput;
      }
  }
  if (nothing_to_do) {
    say << "vdcloth: the run in " << dir << " is done (" << frames << " frames); nothing to resume" << std::endl;
    return kExitOk;
  }
  // Rank 0 sets the directory up (removing an earlier run's files) before any process writes.
  std::optional<FrameTable> ranks, group_table;
  if (const auto status = together(cluster, err, [&] {
        if (!root) output.emplace(RunOutput::joining(dir));
        else if (resume) output.emplace(dir, resume->frame);
        else output.emplace(dir);
        if (root && processes > 1) {
          const int kept = resume ? resume->frame : 0;
          ranks.emplace(dir + "/ranks.csv", kRanksHeader, kept);
          group_table.emplace(dir + "/groups.csv", kGroupsHeader, kept);
        }
      }))
    return *status;
  if (root && resume) output->append_log("resumed at frame " + std::to_string(resume->frame));
  for (const std::string& msg : early_log) output->append_log(msg);
  if (root && processes > sim->groups())
    log(std::to_string(processes) + " processes for " + std::to_string(sim->groups()) + " garment groups: processes " +
        std::to_string(sim->groups()) + " to " + std::to_string(processes - 1) + " have nothing to do");

  int faces_at_start = sim->num_faces();
  if (processes > 1) {
    faces_at_start = 0;
    for (const std::string& f : cluster.all_gather(std::to_string(sim->num_faces()))) faces_at_start += std::stoi(f);
  }
  const bool prerolls = !resume && sim->frame() < 0;
  const int preroll_frames = prerolls ? -sim->frame() : 0;
  const int first = prerolls ? 0 : sim->frame();
  say << "vdcloth: " << sim->name() << ", " << frames << " frames, mode " << sim_mode_name(args.mode) << ", " << threads
      << " thread(s)" << (processes > 1 ? " on each of " + std::to_string(processes) + " processes" : "") << ", "
      << faces_at_start << " faces, output " << dir;
  if (args.perturbation.gravity != 0) say << ", gravity perturbed by " << number_text(args.perturbation.gravity);
  if (args.perturbation.resolution != 0) say << ", resolution perturbed by " << number_text(args.perturbation.resolution);
  if (resume) say << ", resumed at frame " << first;
  if (prerolls) say << ", " << preroll_frames << " frames of pre-roll first";
  if (first < settle_frames) say << ", sized as in adaptive mode up to frame " << settle_frames << " (view.settle: the drape forms first)";
  say << std::endl;

  auto t0 = std::chrono::steady_clock::now();
  auto usage = [&] { return process_usage(before, ticks_at_start, seconds_since(t0)); };
  int done = first;
  // What rank 0 knows of every group: its garments' sizes after the last frame, its seconds
  // since the last checkpoint, and where it has been.
  const auto groups = static_cast<std::size_t>(sim->groups());
  const bool moves_any_frame = !sim->restart_changes_results();
  std::vector<std::vector<GarmentSize>> sizes(groups);
  for (std::size_t k = 0; k < sim->parts().size(); ++k) sizes[static_cast<std::size_t>(sim->here()[k])] = garment_sizes(*sim->parts()[k]);
  std::vector<double> group_seconds(groups, 0.0);
  std::vector<int> group_frames(groups, 0);
  nlohmann::json distribution;
  if (processes > 1) {
    distribution = {{"processes", processes}, {"start", owner}, {"moves", nlohmann::json::array()}};
  }
  auto summary = [&](const std::string& status, const std::string& error) {
    nlohmann::json j = output->summary(*sim, sizes, status, error, usage(), segments, done, threads, args.perturbation);
    if (processes > 1) {
      j["distribution"] = distribution;
      j["distribution"]["rebuild_seconds_per_face"] = rebuild_seconds_per_face;
    }
    return j;
  };
  // Rank 0's checkpoints, written while the next frames are made; every way out of the run
  // waits for the last one (finish_checkpoints), so that a resume finds it.
  CheckpointWriter checkpoints;
  auto finish_checkpoints = [&] {
    if (const std::string failed = checkpoints.finish(); !failed.empty()) log(failed + "; a resume goes on from the checkpoint before it");
  };
  // A run that cannot go on says why and how far it got, in summary.json (if it can still be
  // written) and on the error stream.
  auto stop_part_way = [&](const Failure& f) {
    if (line_open) out << "\n";
    if (!root) return kExitSimulationFailed;
    finish_checkpoints();
    try {
      output->write_summary(summary("failed", f.line()));
    } catch (const std::exception&) {  // the error stream still says why
    }
    err << "vdcloth: " << f.line() << " (frames 0 to " << done << " are in " << dir << ")" << std::endl;
    output->append_log(f.line() + " (at frame " + std::to_string(done) + ")");
    return kExitSimulationFailed;
  };
  auto leave_last_words = [&] {
    if (last_words && root)
      last_words->leave(dir + "/summary.json", summary("failed", ""), dir + "/" + kLogFile,
                        " (frames 0 to " + std::to_string(done) + " are in " + dir + ")");
  };

  double waiting = 0, moving = 0;  // this process's, to report with the next frame
  std::vector<ProcessReport> previous;  // rank 0: the last frame's reports, for its ranks.csv rows
  // One frame on every process: each steps its groups and writes their files, rank 0 gathers
  // the reports, writes the row, the checkpoint and ranks.csv and decides the moves, every
  // process makes them. Returns the frame of the whole (rank 0), or the failure that ends the run.
  auto frame = [&](bool shot) -> std::pair<FrameStats, Failure> {
    const auto start = std::chrono::steady_clock::now();
    ProcessReport mine;
    const int next = sim->frame() + 1;
    const bool checkpoint = shot && args.checkpoint_every > 0 && (next % args.checkpoint_every == 0 || next == frames);
    // Groups may move where the solvers restart anyway (a checkpoint) or, when the linear solver
    // carries nothing that changes a result, after any frame: a group rebuilt elsewhere from its
    // part then goes on exactly as it would have here (nothing the collider finds depends on its
    // hierarchies).
    const bool balancing = processes > 1 && shot && next < frames && (checkpoint || moves_any_frame);
    try {
      if (shot && next == 1 && args.mesh_every > 0 && !resume) {
        const auto w = std::chrono::steady_clock::now();
        output->write_frame(*sim, 0);
        mine.output_seconds += seconds_since(w);
      }
      mine.parts = sim->step_parts();
      if (shot && args.mesh_every > 0 && next % args.mesh_every == 0) {
        const auto w = std::chrono::steady_clock::now();
        output->write_frame(*sim, next);
        mine.output_seconds += seconds_since(w);
      }
      for (const auto& part : sim->parts()) mine.sizes.push_back(garment_sizes(*part));
      if (checkpoint) {
        const auto w = std::chrono::steady_clock::now();
        sim->restart_solvers();
        for (const auto& part : sim->parts()) mine.checkpoint_parts.push_back(checkpoint_part(*part));
        mine.output_seconds += seconds_since(w);
      }
    } catch (...) {
      const Failure f = failure_of(std::current_exception());
      mine.failed_as = f.what.empty() ? "unexpected error" : f.what;
      mine.failure = f.why;
    }
    mine.busy_seconds = seconds_since(start);
    mine.waiting_seconds = waiting;
    mine.moving_seconds = moving;
    mine.rebuild_seconds_per_face = rebuild_seconds_per_face;
    const auto exchange = std::chrono::steady_clock::now();
    const std::vector<std::string> reports = cluster.gather(encode(mine));
    FrameStats total;  // rank 0's: the others know only its number
    total.frame = next;
    Failure failure;
    FramePlan plan;
    if (root) {
      std::vector<ProcessReport> all;
      for (const std::string& r : reports) all.push_back(decode_report(r));
      std::vector<PartFrame> parts;
      std::vector<std::string> blocks(groups);
      for (std::size_t r = 0; r < all.size(); ++r) {
        const ProcessReport& rep = all[r];
        if (!rep.failure.empty() && failure.status == kExitOk) failure = {kExitSimulationFailed, rep.failed_as, rep.failure};
        for (std::size_t k = 0; k < rep.parts.size(); ++k) {
          const auto g = static_cast<std::size_t>(rep.parts[k].group);
          parts.push_back(rep.parts[k]);
          if (k < rep.sizes.size()) sizes[g] = rep.sizes[k];
          if (k < rep.checkpoint_parts.size()) blocks[g] = rep.checkpoint_parts[k];
          group_seconds[g] += rep.parts[k].seconds;
          ++group_frames[g];
        }
        if (rep.rebuild_seconds_per_face > 0) rebuild_seconds_per_face = std::max(rebuild_seconds_per_face, rep.rebuild_seconds_per_face);
      }
      std::sort(parts.begin(), parts.end(), [](const PartFrame& a, const PartFrame& b) { return a.group < b.group; });
      total = total_of(parts);
      total.frame = next;  // a process without groups reported none
      total.seconds = seconds_since(start) - mine.output_seconds;
      if (failure.status == kExitOk && shot) {
        try {
          if (ranks && !previous.empty())  // the last frame's row: its waiting and moving came with this one's reports
            for (std::size_t r = 0; r < all.size(); ++r) ranks->process_row(next - 1, static_cast<int>(r), previous[r], all[r].waiting_seconds, all[r].moving_seconds);
          output->write_stats_row(total);
          if (group_table)
            for (const PartFrame& p : parts) group_table->group_row(sim->group_scene(p.group).garments.front().group, owner[static_cast<std::size_t>(p.group)], p);
          if (checkpoint) {
            progress.usage = usage();
            const std::string failed = checkpoints.start(dir + "/" + kCheckpointFile, progress, args.mode, next, std::move(blocks));
            if (!failed.empty()) log(failed + "; the run goes on, resumable from its previous checkpoint");
          }
          // Moves: each group's mean seconds a frame since the last look, over the frames to the next.
          if (balancing) {
            std::vector<double> per_frame(groups, 0.0), move_seconds(groups, 0.0);
            for (std::size_t g = 0; g < groups; ++g) {
              per_frame[g] = group_frames[g] > 0 ? group_seconds[g] / group_frames[g] : 0.0;
              double faces = 0;
              for (const GarmentSize& s : sizes[g]) faces += s.faces;
              move_seconds[g] = faces * rebuild_seconds_per_face;
            }
            if (args.force_moves)
              for (std::size_t g = 0; g < groups; ++g) plan.moves.push_back({static_cast<int>(g), owner[g], (owner[g] + 1) % processes});
            else
              plan.moves = rebalance(owner, per_frame, move_seconds, processes, moves_any_frame ? 1 : std::min(args.checkpoint_every, frames - next));
            for (const GroupMove& m : plan.moves) {
              log("frame " + std::to_string(next) + ": group " + sim->group_scene(m.group).garments.front().group + " moves from process " +
                  std::to_string(m.from) + " to process " + std::to_string(m.to) + " (" + number_text(per_frame[static_cast<std::size_t>(m.group)]) +
                  " s a frame, about " + number_text(move_seconds[static_cast<std::size_t>(m.group)]) + " s to move)");
              distribution["moves"].push_back({{"frame", next}, {"group", sim->group_scene(m.group).garments.front().group},
                                               {"from", m.from}, {"to", m.to}, {"seconds_a_frame", per_frame[static_cast<std::size_t>(m.group)]},
                                               {"move_seconds", move_seconds[static_cast<std::size_t>(m.group)]}});
              owner[static_cast<std::size_t>(m.group)] = m.to;
            }
            std::fill(group_seconds.begin(), group_seconds.end(), 0.0);
            std::fill(group_frames.begin(), group_frames.end(), 0);
          }
        } catch (...) {
          failure = failure_of(std::current_exception());
        }
      }
      plan.stop = failure.status != kExitOk;
      previous.clear();
      if (shot)
        for (ProcessReport& r : all) {
          r.checkpoint_parts.clear();
          previous.push_back(std::move(r));
        }
    }
    plan = decode_plan(cluster.broadcast(encode(plan)));
    waiting = seconds_since(exchange);
    // Each move in the plan's order: the sender and the receiver meet at it, the others go on.
    const auto moves_start = std::chrono::steady_clock::now();
    std::map<int, std::string> blocks_here;  // this checkpoint's part of each group here (none between checkpoints)
    for (std::size_t k = 0; k < mine.checkpoint_parts.size(); ++k) blocks_here[sim->here()[k]] = std::move(mine.checkpoint_parts[k]);
    if (!plan.stop) try {
      for (const GroupMove& m : plan.moves) {
        if (m.from == cluster.rank()) {
          const auto made = blocks_here.find(m.group);
          if (made != blocks_here.end()) {
            cluster.send(m.to, made->second);
          } else {  // between checkpoints: the group's part made for the move
            cluster.send(m.to, checkpoint_part(sim->part(m.group)));
          }
          sim->drop(m.group);
        } else if (m.to == cluster.rank()) {
          const auto received = std::chrono::steady_clock::now();
          ResumePoint point = read_checkpoint_part(cluster.receive(m.from), next, "group " + std::to_string(m.group) + " from process " + std::to_string(m.from));
          double faces = 0;
          for (const Mesh& mesh : point.garments) faces += mesh.num_faces();
          sim->adopt(m.group, std::move(point), "group " + std::to_string(m.group));
          if (faces > 0) rebuild_seconds_per_face = seconds_since(received) / faces;
        }
      }
    } catch (const std::exception& e) {  // the others wait for this process: all end at once
      err << "vdcloth: process " << cluster.rank() << ": moving a group failed: " << e.what() << std::endl;
      cluster.abort(kExitSimulationFailed);
    }
    moving = seconds_since(moves_start);
    if (plan.stop && failure.status == kExitOk) failure = {kExitSimulationFailed, "stopped", "another process failed"};
    return {total, failure};
  };

  try {
    leave_last_words();
    const Scene& shot = sim->group_scene(0);
    if (root && shot.camera) write_camera_files(*shot.camera, shot.frame_time, frames, dir);
    else if (root) remove_camera_files(dir);  // of an earlier run of another scene
    if (prerolls) {
      // Before the shot, characters move from the pose their garments were made in into the
      // shot's first pose; nothing of it is written (Scene::preroll_frames).
      while (sim->frame() < 0) {
        const auto [s, failure] = frame(false);
        if (failure.status != kExitOk) return stop_part_way(failure);
        std::ostringstream line;
        line << "pre-roll frame " << s.frame << "  " << std::fixed << std::setprecision(3) << s.seconds << " s/frame  " << s.faces << " faces";
        if (interactive) {
          say << "\r" << line.str() << "   " << std::flush;
          line_open = root;
        } else {
          say << line.str() << "\n" << std::flush;
        }
      }
    }
    while (done < frames) {
      const auto [s, failure] = frame(true);
      if (failure.status != kExitOk) return stop_part_way(failure);
      done = s.frame;
      leave_last_words();
      double elapsed = seconds_since(t0);
      double left = elapsed / (done - first) * (frames - done);
      std::ostringstream line;
      line << "frame " << done << " of " << frames << "  " << std::fixed << std::setprecision(3) << s.seconds << " s/frame  "
           << s.faces << " faces  " << format_duration(left) << " left";
      if (interactive) {
        say << "\r" << line.str() << "   " << std::flush;
        line_open = root;
      } else {
        say << line.str() << "\n" << std::flush;
      }
    }
    // The last frame's waiting, for ranks.csv.
    if (processes > 1) {
      BinaryWriter w;
      w.value(waiting);
      w.value(moving);
      const std::vector<std::string> last = cluster.gather(w.bytes());
      if (root && !previous.empty())
        for (std::size_t r = 0; r < last.size(); ++r) {
          BinaryReader in(last[r].data(), last[r].size());
          const double waited = in.value<double>();
          ranks->process_row(done, static_cast<int>(r), previous[r], waited, in.value<double>());
        }
    }
  } catch (...) {
    // Outside the frames' exchange (rank 0's own files, a move): the other processes would
    // wait for this one forever, so the run ends as a whole.
    const int status = stop_part_way(failure_of(std::current_exception()));
    if (processes > 1) cluster.abort(status);
    return status;
  }
  if (line_open) out << "\n";
  if (!root) return kExitOk;
  finish_checkpoints();
  output->write_summary(summary("done", ""));
  const double this_segment = seconds_since(t0);
  out << "vdcloth: done, " << done - first << " frames in " << format_duration(this_segment) << " ("
      << std::fixed << std::setprecision(3) << this_segment / std::max(done - first, 1) << " s/frame); results in " << dir << std::endl;
  out << "vdcloth: to see it in a browser: vdcloth report " << dir << " writes " << dir << "/report/index.html\n";
  if (args.mesh_every > 0 && sim->group_scene(0).camera)
    out << "vdcloth: to look at it: vdcloth render " << args.scene << " " << dir << " draws it through the shot camera into "
        << dir << "/render/ (add --video for an MP4, --colour view --wireframe for the mesh); " << dir
        << "/frames/ holds the OBJ and PLY meshes, " << dir << "/camera.chan the camera\n";
  return kExitOk;
}

}  // namespace vdc
