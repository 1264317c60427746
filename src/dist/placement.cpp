#include "dist/placement.hpp"

#include <algorithm>

#include "core/task_order.hpp"

namespace vdc {

namespace {
std::vector<double> loads(const std::vector<int>& owner, const std::vector<double>& seconds, int processes) {
  std::vector<double> load(static_cast<std::size_t>(processes), 0.0);
  for (std::size_t g = 0; g < owner.size(); ++g) load[static_cast<std::size_t>(owner[g])] += seconds[g];
  return load;
}
}  // namespace

std::vector<int> place_longest_first(const std::vector<double>& cost, int processes) {
  std::vector<int> owner(cost.size(), 0);
  std::vector<double> load(static_cast<std::size_t>(processes), 0.0);
  for (int g : largest_first(cost)) {
    const auto least = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    owner[static_cast<std::size_t>(g)] = static_cast<int>(least);
    load[least] += cost[static_cast<std::size_t>(g)];
  }
  return owner;
}

std::vector<GroupMove> rebalance(const std::vector<int>& owner_now, const std::vector<double>& seconds, const std::vector<double>& move_seconds,
                                 int processes, int frames_ahead) {
  std::vector<int> owner = owner_now;
  std::vector<char> moved(owner.size(), 0);
  std::vector<GroupMove> moves;
  for (std::size_t round = 0; round < owner.size(); ++round) {
    std::vector<double> load = loads(owner, seconds, processes);
    const auto busiest = static_cast<int>(std::max_element(load.begin(), load.end()) - load.begin());
    const double makespan = load[static_cast<std::size_t>(busiest)];
    const auto least = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    double best_net = 0;
    GroupMove best{-1, busiest, least};
    for (std::size_t g = 0; g < owner.size(); ++g) {
      if (owner[g] != busiest || moved[g]) continue;
      // The busiest process's load falls by the group's; the pair's greater load is the gain's measure.
      const double after = std::max(makespan - seconds[g], load[static_cast<std::size_t>(least)] + seconds[g]);
      const double net = (makespan - after) * frames_ahead - move_seconds[g];
      if (net > best_net) {
        best_net = net;
        best.group = static_cast<int>(g);
      }
    }
    if (best.group < 0) break;
    owner[static_cast<std::size_t>(best.group)] = best.to;
    moved[static_cast<std::size_t>(best.group)] = 1;
    moves.push_back(best);
  }
  return moves;
}

}  // namespace vdc
