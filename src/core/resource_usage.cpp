#include "core/resource_usage.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

namespace vdc {

CpuTicks machine_ticks() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  CpuTicks t;
  if (!(stat >> cpu) || cpu != "cpu") return t;
  long long v = 0;
  for (int i = 0; i < 8 && stat >> v; ++i) {
    t.total += v;
    if (i == 7) t.steal = v;
  }
  return t;
}

long resident_kib() {
  std::ifstream statm("/proc/self/statm");
  long size_pages = 0, resident_pages = 0;
  if (!(statm >> size_pages >> resident_pages)) return 0;
  return resident_pages * (::sysconf(_SC_PAGESIZE) / 1024);
}

ResourceUsage process_usage(const ResourceUsage& before, const CpuTicks& start, double wall_now) {
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  ResourceUsage u = before;
  u.wall_seconds += wall_now;
  u.cpu_seconds += static_cast<double>(self.ru_utime.tv_sec + self.ru_stime.tv_sec) +
                   1e-6 * static_cast<double>(self.ru_utime.tv_usec + self.ru_stime.tv_usec);
  u.peak_kib = std::max(u.peak_kib, static_cast<long>(self.ru_maxrss));
  const CpuTicks now = machine_ticks();
  if (now.total > start.total) {
    u.machine.total += now.total - start.total;
    u.machine.steal += now.steal - start.steal;
  }
  return u;
}

MachineDescription describe_machine() {
  MachineDescription m;
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) == 0) m.host = host;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; m.cpu.empty() && std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0)
      if (const auto start = line.find_first_not_of(" \t", line.find(':') + 1); line.find(':') != std::string::npos && start != std::string::npos)
        m.cpu = line.substr(start);
  m.cores = static_cast<int>(std::thread::hardware_concurrency());
  return m;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace vdc
