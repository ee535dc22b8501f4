#pragma once

// The bench's clocks and what it makes of repeated times: wall time from a steady clock, the
// process's CPU time over all its threads (llvmpipe runs the kernels on worker threads of the
// process), and the median of rounds.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace sandphys::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline double processCpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

/// The median of `values` (the mean of the middle two for an even count); 0 for none.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

}  // namespace sandphys::bench
