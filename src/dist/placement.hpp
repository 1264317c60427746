// Which process of a run steps which garment group. Groups start on processes longest
// processing time first (Graham 1969) by their predicted cost, and move between processes at
// checkpoints, one at a time from the busiest process, when the measured costs say the move
// pays for itself before the next checkpoint.
#pragma once
#include <vector>

namespace vdc {

// The process (0 .. processes - 1) of each group: the costliest group first, each to the least
// loaded process (the lowest rank among equals).
std::vector<int> place_longest_first(const std::vector<double>& cost, int processes);

struct GroupMove {
  int group = 0, from = 0, to = 0;
};

// Moves of groups from `owner` (a process per group). `seconds`: each group's measured seconds
// a frame; a process's load is the sum of its groups'. Each move takes the group off the
// busiest process to the least loaded one (the lowest rank among equals) that lowers the
// greater of the two loads most; it is made only when that gain over `frames_ahead` frames
// exceeds `move_seconds` (the group's measured cost of being sent and rebuilt). Moves follow
// while one pays, at most one a group.
std::vector<GroupMove> rebalance(const std::vector<int>& owner, const std::vector<double>& seconds, const std::vector<double>& move_seconds,
                                 int processes, int frames_ahead);

}  // namespace vdc
