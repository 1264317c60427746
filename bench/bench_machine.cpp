// The machine's own rates, the yardsticks a stage's time is held against in bench/RESULTS.md:
// dense multiply-adds through the BLAS the factorization calls (at a supernode update's sizes and
// large), streaming bandwidth (a triad over arrays past the last cache, on one and two threads),
// and loads from random places past the last cache (independent, and each waiting on the last).
// Run: build/bench/vdcloth_bench --benchmark_filter='Machine'
#include <benchmark/benchmark.h>

#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "physics/cholmod_use.hpp"

extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* b, const int* ldb, const double* beta, double* c, const int* ldc);
}

namespace vdc {
namespace {

// C (m x m) = A B^T with A and B m x k, the shape of a supernode's update to its ancestor, on the
// calling thread (as the factorization calls it).
void BM_MachineDgemm(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  std::vector<double> a(static_cast<std::size_t>(m) * k, 0.5), b(static_cast<std::size_t>(m) * k, 0.25),
      c(static_cast<std::size_t>(m) * m, 0.0);
  const double one = 1.0, zero = 0.0;
  for (auto _ : state) {
    cholmod_serial([&] { dgemm_("N", "T", &m, &m, &k, &one, a.data(), &m, b.data(), &m, &zero, c.data(), &m); });
    benchmark::DoNotOptimize(c.data());
  }
  state.counters["flops"] = benchmark::Counter(2.0 * m * m * k, benchmark::Counter::kIsIterationInvariantRate);
}

// a = b + s c over three arrays of 32 MiB each: 24 bytes read or written an element (the
// write's line fill not counted), on state.range(0) threads.
void BM_MachineTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const std::size_t n = std::size_t{32} << 17;  // 4 Mi doubles
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const auto size = static_cast<int64_t>(n);
  for (auto _ : state) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int64_t i = 0; i < size; ++i) a[static_cast<std::size_t>(i)] = b[static_cast<std::size_t>(i)] + 1.5 * c[static_cast<std::size_t>(i)];
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["bytes"] = benchmark::Counter(24.0 * static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

// 8 Mi random places in 64 MiB: summed in random order (independent loads), and followed as a
// single cycle (each load's address the last one's value).
std::vector<uint32_t> random_cycle(std::size_t n) {
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin() + 1, order.end(), std::mt19937(7));
  std::vector<uint32_t> next(n);
  for (std::size_t i = 0; i < n; ++i) next[order[i]] = order[(i + 1) % n];
  return next;
}

void BM_MachineRandomLoads(benchmark::State& state) {
  const std::size_t n = std::size_t{1} << 23;
  const std::vector<uint32_t> next = random_cycle(n);
  std::vector<double> values(n, 1.0);
  const bool dependent = state.range(0) != 0;
  for (auto _ : state) {
    double sum = 0;
    uint32_t at = 0;
    if (dependent) {
      for (std::size_t i = 0; i < n; ++i) at = next[at];
      sum = at;
    } else {
      for (std::size_t i = 0; i < n; ++i) sum += values[next[i]];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["loads"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(dependent ? "dependent" : "independent");
}

}  // namespace

BENCHMARK(BM_MachineDgemm)->Args({24, 24})->Args({48, 24})->Args({96, 48})->Args({192, 96})->Args({512, 512})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MachineTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MachineRandomLoads)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace vdc
