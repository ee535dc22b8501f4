#pragma once

// The bench's clocks: wall time from a steady clock, and the process's CPU time over all its
// threads (llvmpipe runs the kernels on worker threads of the process).
#include <chrono>
#include <ctime>

namespace sandphys::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline double processCpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

}  // namespace sandphys::bench
