#include "app/run_frame.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "core/binary_io.hpp"
#include "core/stopwatch.hpp"
#include "dist/placement.hpp"
#include "output/checkpoint.hpp"

namespace vdc {

FrameExchange::FrameExchange(const RunArgs& args, const Cluster& cluster, RunSetup& setup, RunOutput& output, RunLog& log,
                             std::function<ResourceUsage()> usage, std::optional<FrameTable> ranks, std::optional<FrameTable> groups)
    : args_(args), cluster_(cluster), setup_(setup), sim_(*setup.sim), output_(output), log_(log), usage_(std::move(usage)),
      ranks_(std::move(ranks)), group_table_(std::move(groups)), groups_(static_cast<std::size_t>(sim_.groups())),
      moves_any_frame_(!sim_.restart_changes_results()), sizes_(groups_), group_seconds_(groups_, 0.0), group_frames_(groups_, 0) {
  for (std::size_t k = 0; k < sim_.parts().size(); ++k) sizes_[static_cast<std::size_t>(sim_.here()[k])] = garment_sizes(*sim_.parts()[k]);
  if (cluster_.size() > 1)
    distribution_ = {{"processes", cluster_.size()}, {"start", setup_.owner}, {"moves", nlohmann::json::array()}};
}

FrameOutcome FrameExchange::step(bool shot) {
  const auto start = std::chrono::steady_clock::now();
  const int next = sim_.frame() + 1;
  const bool checkpoint = shot && args_.checkpoint_every > 0 && (next % args_.checkpoint_every == 0 || next == setup_.frames);
  // Groups may move where the solvers restart anyway (a checkpoint) or, when the linear solver
  // carries nothing that changes a result, after any frame: a group rebuilt elsewhere from its
  // part then goes on exactly as it would have here (nothing the collider finds depends on its
  // hierarchies).
  const bool balancing = cluster_.size() > 1 && shot && next < setup_.frames && (checkpoint || moves_any_frame_);
  ProcessReport mine = step_here(next, shot, checkpoint);
  mine.busy_seconds = seconds_since(start);
  mine.waiting_seconds = waiting_;
  mine.moving_seconds = moving_;
  mine.rebuild_seconds_per_face = setup_.rebuild_seconds_per_face;
  const auto exchange = std::chrono::steady_clock::now();
  const std::vector<std::string> reports = cluster_.gather(encode(mine));
  FrameOutcome outcome;
  outcome.stats.frame = next;
  FramePlan plan;
  if (cluster_.root()) plan = decide(reports, next, shot, checkpoint, balancing, [&] { return seconds_since(start) - mine.output_seconds; }, outcome);
  plan = decode_plan(cluster_.broadcast(encode(plan)));
  waiting_ = seconds_since(exchange);
  const auto moves_start = std::chrono::steady_clock::now();
  make_moves(plan, mine, next);
  moving_ = seconds_since(moves_start);
  if (plan.stop && outcome.failure.status == kExitOk) outcome.failure = {kExitSimulationFailed, "stopped", "another process failed"};
  return outcome;
}

// This process's groups one frame on, their files written and, at a checkpoint, their parts made.
ProcessReport FrameExchange::step_here(int next, bool shot, bool checkpoint) {
  ProcessReport mine;
  auto timed_output = [&](auto&& write) {
    const auto w = std::chrono::steady_clock::now();
    write();
    mine.output_seconds += seconds_since(w);
  };
  try {
    if (shot && next == 1 && args_.mesh_every > 0 && !setup_.resume) timed_output([&] { output_.write_frame(sim_, 0); });
    mine.parts = sim_.step_parts();
    if (shot && args_.mesh_every > 0 && next % args_.mesh_every == 0) timed_output([&] { output_.write_frame(sim_, next); });
    for (const auto& part : sim_.parts()) mine.sizes.push_back(garment_sizes(*part));
    if (checkpoint)
      timed_output([&] {
        sim_.restart_solvers();
        for (const auto& part : sim_.parts()) mine.checkpoint_parts.push_back(checkpoint_part(*part));
      });
  } catch (...) {
    const Failure f = failure_of(std::current_exception());
    mine.failed_as = f.what.empty() ? "unexpected error" : f.what;
    mine.failure = f.why;
  }
  return mine;
}

// Rank 0: every process's report of the frame taken in; the frame's rows, checkpoint and moves.
FramePlan FrameExchange::decide(const std::vector<std::string>& reports, int next, bool shot, bool checkpoint, bool balancing,
                                const std::function<double()>& frame_seconds, FrameOutcome& outcome) {
  std::vector<ProcessReport> all;
  for (const std::string& r : reports) all.push_back(decode_report(r));
  std::vector<PartFrame> parts;
  std::vector<std::string> blocks(groups_);
  take_reports(all, outcome.failure, parts, blocks);
  std::sort(parts.begin(), parts.end(), [](const PartFrame& a, const PartFrame& b) { return a.group < b.group; });
  outcome.stats = total_of(parts);
  outcome.stats.frame = next;  // a process without groups reported none
  outcome.stats.seconds = frame_seconds();
  FramePlan plan;
  if (outcome.failure.status == kExitOk && shot) {
    try {
      write_rows(outcome.stats, all, parts, checkpoint, std::move(blocks));
      if (balancing) plan.moves = plan_moves(next);
    } catch (...) {
      outcome.failure = failure_of(std::current_exception());
    }
  }
  plan.stop = outcome.failure.status != kExitOk;
  previous_.clear();
  if (shot)
    for (ProcessReport& r : all) {
      r.checkpoint_parts.clear();
      previous_.push_back(std::move(r));
    }
  return plan;
}

void FrameExchange::take_reports(const std::vector<ProcessReport>& all, Failure& failure, std::vector<PartFrame>& parts,
                                 std::vector<std::string>& blocks) {
  for (const ProcessReport& rep : all) {
    if (!rep.failure.empty() && failure.status == kExitOk) failure = {kExitSimulationFailed, rep.failed_as, rep.failure};
    for (std::size_t k = 0; k < rep.parts.size(); ++k) {
      const auto g = static_cast<std::size_t>(rep.parts[k].group);
      parts.push_back(rep.parts[k]);
      if (k < rep.sizes.size()) sizes_[g] = rep.sizes[k];
      if (k < rep.checkpoint_parts.size()) blocks[g] = rep.checkpoint_parts[k];
      group_seconds_[g] += rep.parts[k].seconds;
      ++group_frames_[g];
    }
    if (rep.rebuild_seconds_per_face > 0)
      setup_.rebuild_seconds_per_face = std::max(setup_.rebuild_seconds_per_face, rep.rebuild_seconds_per_face);
  }
}

void FrameExchange::write_rows(const FrameStats& total, const std::vector<ProcessReport>& all, const std::vector<PartFrame>& parts,
                               bool checkpoint, std::vector<std::string> blocks) {
  const int next = total.frame;
  if (ranks_ && !previous_.empty())  // the last frame's row: its waiting and moving came with this one's reports
    for (std::size_t r = 0; r < all.size(); ++r)
      ranks_->process_row(next - 1, static_cast<int>(r), previous_[r], all[r].waiting_seconds, all[r].moving_seconds);
  output_.write_stats_row(total);
  if (group_table_)
    for (const PartFrame& p : parts) group_table_->group_row(group_name(p.group), setup_.owner[static_cast<std::size_t>(p.group)], p);
  if (checkpoint) {
    setup_.progress.usage = usage_();
    const std::string failed =
        checkpoints_.start(setup_.dir + "/" + kCheckpointFile, setup_.progress, args_.mode, next, std::move(blocks));
    if (!failed.empty()) log_.warn(failed + "; the run goes on, resumable from its previous checkpoint");
  }
}

// Moves: each group's mean seconds a frame since the last look, over the frames to the next.
std::vector<GroupMove> FrameExchange::plan_moves(int next) {
  const int processes = cluster_.size();
  std::vector<int>& owner = setup_.owner;
  std::vector<double> per_frame(groups_, 0.0), move_seconds(groups_, 0.0);
  for (std::size_t g = 0; g < groups_; ++g) {
    per_frame[g] = group_frames_[g] > 0 ? group_seconds_[g] / group_frames_[g] : 0.0;
    double faces = 0;
    for (const GarmentSize& s : sizes_[g]) faces += s.faces;
    move_seconds[g] = faces * setup_.rebuild_seconds_per_face;
  }
  std::vector<GroupMove> moves;
  if (args_.force_moves)
    for (std::size_t g = 0; g < groups_; ++g) moves.push_back({static_cast<int>(g), owner[g], (owner[g] + 1) % processes});
  else
    moves = rebalance(owner, per_frame, move_seconds, processes,
                      moves_any_frame_ ? 1 : std::min(args_.checkpoint_every, setup_.frames - next));
  for (const GroupMove& m : moves) {
    const auto g = static_cast<std::size_t>(m.group);
    log_.warn("frame " + std::to_string(next) + ": group " + group_name(m.group) + " moves from process " + std::to_string(m.from) +
              " to process " + std::to_string(m.to) + " (" + number_text(per_frame[g]) + " s a frame, about " +
              number_text(move_seconds[g]) + " s to move)");
    distribution_["moves"].push_back({{"frame", next}, {"group", group_name(m.group)}, {"from", m.from}, {"to", m.to},
                                      {"seconds_a_frame", per_frame[g]}, {"move_seconds", move_seconds[g]}});
    owner[g] = m.to;
  }
  std::fill(group_seconds_.begin(), group_seconds_.end(), 0.0);
  std::fill(group_frames_.begin(), group_frames_.end(), 0);
  return moves;
}

// Each move in the plan's order: the sender and the receiver meet at it, the others go on.
void FrameExchange::make_moves(const FramePlan& plan, ProcessReport& mine, int next) {
  std::map<int, std::string> blocks_here;  // this checkpoint's part of each group here (none between checkpoints)
  for (std::size_t k = 0; k < mine.checkpoint_parts.size(); ++k) blocks_here[sim_.here()[k]] = std::move(mine.checkpoint_parts[k]);
  if (plan.stop) return;
  try {
    for (const GroupMove& m : plan.moves) {
      if (m.from == cluster_.rank()) {
        const auto made = blocks_here.find(m.group);
        // Between checkpoints: the group's part made for the move.
        cluster_.send(m.to, made != blocks_here.end() ? made->second : checkpoint_part(sim_.part(m.group)));
        sim_.drop(m.group);
      } else if (m.to == cluster_.rank()) {
        const auto received = std::chrono::steady_clock::now();
        ResumePoint point = read_checkpoint_part(cluster_.receive(m.from), next,
                                                 "group " + std::to_string(m.group) + " from process " + std::to_string(m.from));
        double faces = 0;
        for (const Mesh& mesh : point.garments) faces += mesh.num_faces();
        sim_.adopt(m.group, std::move(point), "group " + std::to_string(m.group));
        if (faces > 0) setup_.rebuild_seconds_per_face = seconds_since(received) / faces;
      }
    }
  } catch (const std::exception& e) {  // the others wait for this process: all end at once
    log_.error("process " + std::to_string(cluster_.rank()) + ": moving a group failed: " + e.what());
    cluster_.abort(kExitSimulationFailed);
  }
}

const std::string& FrameExchange::group_name(int group) const { return sim_.group_scene(group).garments.front().group; }

void FrameExchange::finish_tables(int done) {
  if (cluster_.size() == 1) return;
  BinaryWriter w;
  w.value(waiting_);
  w.value(moving_);
  const std::vector<std::string> last = cluster_.gather(w.bytes());
  if (!cluster_.root() || previous_.empty()) return;
  for (std::size_t r = 0; r < last.size(); ++r) {
    BinaryReader in(last[r].data(), last[r].size());
    const double waited = in.value<double>();
    ranks_->process_row(done, static_cast<int>(r), previous_[r], waited, in.value<double>());
  }
}

nlohmann::json FrameExchange::summary(const std::string& status, const std::string& error, int done) const {
  nlohmann::json j = output_.summary(sim_, sizes_, status, error, usage_(), setup_.segments, done, setup_.threads, args_.perturbation);
  if (cluster_.size() > 1) {
    j["distribution"] = distribution_;
    j["distribution"]["rebuild_seconds_per_face"] = setup_.rebuild_seconds_per_face;
  }
  return j;
}

void FrameExchange::finish_checkpoints() {
  if (const std::string failed = checkpoints_.finish(); !failed.empty())
    log_.warn(failed + "; a resume goes on from the checkpoint before it");
}

}  // namespace vdc
