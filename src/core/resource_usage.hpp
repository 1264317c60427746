// What a run costs the machine: wall and CPU time, peak memory, and the host's steal while it
// ran, summed over the pieces of a run that was stopped and resumed.
#pragma once
#include <string>

namespace vdc {

// The machine's CPU time from /proc/stat's first line, in clock ticks: the total (user, nice,
// system, idle, iowait, irq, softirq, steal) and the steal, time a virtual machine's CPUs were
// ready but the host ran something else. Zeros where /proc/stat cannot be read.
struct CpuTicks {
  long long total = 0, steal = 0;
};
CpuTicks machine_ticks();

struct ResourceUsage {
  double wall_seconds = 0;  // the frame loop's wall time
  double cpu_seconds = 0;   // user and system CPU time of the process, all threads
  long peak_kib = 0;        // peak resident memory
  CpuTicks machine;         // the machine's ticks meanwhile
  // Share of the machine's CPU time the host took (-1: unknown).
  double steal() const { return machine.total > 0 ? static_cast<double>(machine.steal) / static_cast<double>(machine.total) : -1.0; }
};

// This process's resident memory now, KiB (from /proc/self/statm; 0 where it cannot be read):
// unlike the peak, it falls when memory is given back, so a long run's rows show a leak as growth.
long resident_kib();

// This process's usage so far, added to `before` (the earlier pieces of a resumed run): CPU time
// summed, peak memory the larger, and the machine's ticks since `start`. `wall_seconds` is
// before's plus `wall_now`.
ResourceUsage process_usage(const ResourceUsage& before, const CpuTicks& start, double wall_now);

// The machine a run ran on, as its summary records it: host name, CPU model (/proc/cpuinfo's
// "model name"), cores the process may use. Empty strings where they cannot be read.
struct MachineDescription {
  std::string host, cpu;
  int cores = 0;
};
MachineDescription describe_machine();

// The time now in UTC, as "2026-11-29T11:42:07Z".
std::string utc_now_iso8601();

}  // namespace vdc
