#include "dist/placement.hpp"

#include <algorithm>

#include "core/task_order.hpp"

namespace vdc {

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

// Local search from the current placement (moves and trades off the process with the greatest
// makespan, after Graham's list scheduling): each process's time over the interval is its
// load times the frames ahead plus the cost of the groups it receives.
std::vector<GroupMove> rebalance(const std::vector<int>& owner_now, const std::vector<double>& seconds, const std::vector<double>& move_seconds,
                                 int processes, int frames_ahead) {
  std::vector<int> owner = owner_now;
  std::vector<double> load(static_cast<std::size_t>(processes), 0.0), incoming(load.size(), 0.0);
  for (std::size_t g = 0; g < owner.size(); ++g) load[static_cast<std::size_t>(owner[g])] += seconds[g];
  std::vector<char> moved(owner.size(), 0);
  const auto time_of = [&](std::size_t q) { return load[q] * frames_ahead + incoming[q]; };
  auto shift = [&](std::size_t g, std::size_t from, std::size_t to) {
    owner[g] = static_cast<int>(to);
    moved[g] = 1;
    load[from] -= seconds[g];
    load[to] += seconds[g];
    incoming[to] += move_seconds[g];
  };
  for (std::size_t round = 0; round < owner.size(); ++round) {
    std::size_t busiest = 0;
    for (std::size_t q = 1; q < load.size(); ++q)
      if (time_of(q) > time_of(busiest)) busiest = q;
    // A step must take more than kLeastGain of the busiest process's time off it: a group's
    // seconds change by about a tenth from frame to frame, and a smaller gain is mostly noise.
    const double before = time_of(busiest);
    double best = before * (1 - kLeastGain);
    int give = -1, take = -1;
    std::size_t partner = busiest;
    for (std::size_t g = 0; g < owner.size(); ++g) {
      if (static_cast<std::size_t>(owner[g]) != busiest || moved[g]) continue;
      const double without = before - seconds[g] * frames_ahead;
      for (std::size_t q = 0; q < load.size(); ++q) {
        if (q == busiest) continue;
        const double with = time_of(q) + seconds[g] * frames_ahead + move_seconds[g];
        if (std::max(without, with) < best) best = std::max(without, with), give = static_cast<int>(g), take = -1, partner = q;
        for (std::size_t h = 0; h < owner.size(); ++h) {  // or g traded for a lighter group h of q
          if (static_cast<std::size_t>(owner[h]) != q || moved[h] || seconds[h] >= seconds[g]) continue;
          const double here = without + seconds[h] * frames_ahead + move_seconds[h];
          const double there = with - seconds[h] * frames_ahead;
          if (std::max(here, there) < best) best = std::max(here, there), give = static_cast<int>(g), take = static_cast<int>(h), partner = q;
        }
      }
    }
    if (give < 0) break;
    shift(static_cast<std::size_t>(give), busiest, partner);
    if (take >= 0) shift(static_cast<std::size_t>(take), partner, busiest);
  }
  std::vector<GroupMove> moves;
  for (std::size_t g = 0; g < owner.size(); ++g)
    if (owner[g] != owner_now[g]) moves.push_back({static_cast<int>(g), owner_now[g], owner[g]});
  return moves;
}

}  // namespace vdc
