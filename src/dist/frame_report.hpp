// What the processes of a run say to each other at the end of each frame: each process's
// report to rank 0 (its groups' frames, sizes and checkpoint parts, its time, its failure),
// and rank 0's plan for all (go on or stop, groups to move).
#pragma once
#include <string>
#include <vector>

#include "dist/placement.hpp"
#include "output/run_output.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

struct ProcessReport {
  std::vector<PartFrame> parts;                    // in group order
  std::vector<std::vector<GarmentSize>> sizes;     // of each part's garments after the frame
  std::vector<std::string> checkpoint_parts;       // at a checkpoint: checkpoint_part of each part
  double busy_seconds = 0;      // stepping this frame, writing its files, making its checkpoint parts
  double output_seconds = 0;    // writing its frame files and making its checkpoint parts
  double waiting_seconds = 0;   // in the last frame's exchange, waiting for the others
  double moving_seconds = 0;    // taking groups on or handing them over since the last report
  double rebuild_seconds_per_face = 0;  // of its last part built from a scene or a checkpoint part (0: none yet)
  std::string failed_as, failure;  // what failed ("simulation failed", ...) and why; empty: nothing
};

struct FramePlan {
  bool stop = false;
  std::vector<GroupMove> moves;
};

std::string encode(const ProcessReport& report);
ProcessReport decode_report(const std::string& bytes);
std::string encode(const FramePlan& plan);
FramePlan decode_plan(const std::string& bytes);

}  // namespace vdc
