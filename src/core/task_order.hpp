// Independent tasks on a team of threads, each thread taking the next task of a given order as
// it comes free; with the order longest first (Graham 1969) a costly task does not start last
// and leave the other threads idle. Each task's result must not depend on which thread ran it.
#pragma once
#include <algorithm>
#include <cstdint>
#include <exception>
#include <numeric>
#include <vector>

namespace vdc {

// 0, 1, ..., n - 1.
inline std::vector<int> index_order(std::size_t n) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  return order;
}

// Indices by decreasing cost, ties in index order.
inline std::vector<int> largest_first(const std::vector<double>& cost) {
  std::vector<int> order = index_order(cost.size());
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return cost[static_cast<std::size_t>(a)] > cost[static_cast<std::size_t>(b)]; });
  return order;
}

// Runs body(order[i]) for every i on `team` threads, then rethrows the first exception thrown
// (in index order). A team of one runs outside any OpenMP region: the parallel regions inside a
// task are then not nested, and libgomp reuses its threads for them instead of starting new
// ones for each (a solo-dancer run had started about 150 threads a frame).
template <class F>
void for_each_in_order(const std::vector<int>& order, int team, F&& body) {
  const auto n = static_cast<int>(order.size());
  std::vector<std::exception_ptr> errors(order.size());
  auto run = [&](int i) {
    const int k = order[static_cast<std::size_t>(i)];
    try {
      body(k);
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
    }
  };
  if (team <= 1) {
    for (int i = 0; i < n; ++i) run(i);
  } else {
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
    for (int i = 0; i < n; ++i) run(i);
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// body(i) for every i in [0, n) on `threads` threads, in static blocks. One thread runs a plain
// loop, outside any OpenMP region, so that the regions inside body are not nested ones. body's
// results must not depend on which thread ran it.
template <class F>
void for_each_index(int64_t n, int threads, F&& body) {
  if (threads > 1) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int64_t i = 0; i < n; ++i) body(i);
  } else {
    for (int64_t i = 0; i < n; ++i) body(i);
  }
}

}  // namespace vdc
