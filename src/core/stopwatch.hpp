// Wall-clock seconds, for the timings runs report (never for anything a result depends on).
#pragma once
#include <chrono>

namespace vdc {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace vdc
