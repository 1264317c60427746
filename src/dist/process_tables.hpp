// The tables of a run made by several processes, written by rank 0: DIR/ranks.csv (a row per
// frame and process) and DIR/groups.csv (a row per frame and group).
#pragma once
#include <fstream>
#include <string>

#include "dist/frame_report.hpp"

namespace vdc {

// A table with a row per frame and process or group, kept up to the checkpoint's frame when
// the run is resumed (resume_at > 0). Throws OutputError when it cannot be written.
class FrameTable {
 public:
  FrameTable(const std::string& path, const std::string& header, int resume_at);
  // Process `process`'s row of ranks.csv for `frame`: its report of the frame, and the seconds
  // it then waited for the others and spent moving groups.
  void process_row(int frame, int process, const ProcessReport& r, double waiting, double moving);
  // A group's row of groups.csv: the process that stepped it, its faces and seconds, and 1 when
  // it ran at the far level of detail (FrameStats::far_groups).
  void group_row(const std::string& group, int process, const PartFrame& p);

 private:
  void finish_row();
  std::string path_;
  std::ofstream table_;
};

inline constexpr const char* kRanksHeader = "frame,process,groups,faces,busy_seconds,waiting_seconds,moving_seconds";
inline constexpr const char* kGroupsHeader = "frame,group,process,faces,seconds,far";

}  // namespace vdc
