// One frame of `vdcloth run` on every process of its cluster: each steps its groups and writes
// their files; rank 0 gathers the reports, writes the frame's rows, the checkpoint and
// ranks.csv, and decides which groups move; every process then makes the moves.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/run_failure.hpp"
#include "app/run_log.hpp"
#include "app/run_setup.hpp"
#include "dist/frame_report.hpp"
#include "dist/process_tables.hpp"
#include "output/checkpoint_writer.hpp"

namespace vdc {

// The frame of the whole (rank 0's; the others know only its number), or the failure that
// ends the run.
struct FrameOutcome {
  FrameStats stats;
  Failure failure;
};

class FrameExchange {
 public:
  // `ranks` and `groups`: rank 0's ranks.csv and groups.csv in a run of several processes.
  FrameExchange(const RunArgs& args, const Cluster& cluster, RunSetup& setup, RunOutput& output, RunLog& log,
                std::function<ResourceUsage()> usage, std::optional<FrameTable> ranks, std::optional<FrameTable> groups);
  FrameExchange(const FrameExchange&) = delete;
  FrameExchange& operator=(const FrameExchange&) = delete;

  // The next frame; `shot`: a frame of the shot (written, counted, checkpointed), not of the
  // pre-roll.
  FrameOutcome step(bool shot);
  // After the last frame: its waiting and moving, for ranks.csv's last rows.
  void finish_tables(int done);
  // summary.json's contents after `done` frames.
  nlohmann::json summary(const std::string& status, const std::string& error, int done) const;
  // Waits for the checkpoint being written; says in the log when it failed.
  void finish_checkpoints();

 private:
  ProcessReport step_here(int next, bool shot, bool checkpoint);
  FramePlan decide(const std::vector<std::string>& reports, int next, bool shot, bool checkpoint, bool balancing,
                   const std::function<double()>& frame_seconds, FrameOutcome& outcome);
  void take_reports(const std::vector<ProcessReport>& all, Failure& failure, std::vector<PartFrame>& parts, std::vector<std::string>& blocks);
  void write_rows(const FrameStats& total, const std::vector<ProcessReport>& all, const std::vector<PartFrame>& parts, bool checkpoint,
                  std::vector<std::string> blocks);
  std::vector<GroupMove> plan_moves(int next);
  void make_moves(const FramePlan& plan, ProcessReport& mine, int next);
  const std::string& group_name(int group) const;

  const RunArgs& args_;
  const Cluster& cluster_;
  RunSetup& setup_;
  Ensemble& sim_;
  RunOutput& output_;
  RunLog& log_;
  std::function<ResourceUsage()> usage_;
  std::optional<FrameTable> ranks_, group_table_;
  CheckpointWriter checkpoints_;  // rank 0's, written while the next frames are made
  const std::size_t groups_;
  const bool moves_any_frame_;
  // What rank 0 knows of every group: its garments' sizes after the last frame, its seconds
  // since the last look at the balance, and where it has been.
  std::vector<std::vector<GarmentSize>> sizes_;
  std::vector<double> group_seconds_;
  std::vector<int> group_frames_;
  nlohmann::json distribution_;
  double waiting_ = 0, moving_ = 0;     // this process's, to report with the next frame
  std::vector<ProcessReport> previous_; // rank 0: the last frame's reports, for its ranks.csv rows
};

}  // namespace vdc
