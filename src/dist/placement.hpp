// Which process of a run steps which garment group. Groups start on processes longest
// processing time first (Graham 1969) by their predicted cost, and move between processes at
// checkpoints, given or traded away by the busiest process, when the measured costs say the
// move pays for itself before the next checkpoint.
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
// a frame; a process's time over the next `frames_ahead` frames is the sum of its groups'
// seconds times those frames plus `move_seconds` of each group it receives (the group's
// measured cost of being sent and rebuilt). Step by step, the busiest process gives one of its
// groups to another process, or trades one for a lighter group of another, whichever leaves
// the greater of the two processes' times least; a step is made only when that is below the
// busiest process's time by more than kLeastGain of it, and each group moves at most once.
// The moves are listed by group.
inline constexpr double kLeastGain = 0.01;
std::vector<GroupMove> rebalance(const std::vector<int>& owner, const std::vector<double>& seconds, const std::vector<double>& move_seconds,
                                 int processes, int frames_ahead);

}  // namespace vdc
