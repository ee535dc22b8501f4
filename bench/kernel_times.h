#pragma once

// Per-kernel GPU times (World::kernelTimes, GL timer queries) summed over substeps.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::bench {

/// Per-kernel GPU time, averaged per substep.
struct KernelStep {
  std::string name;
  double millisecondsPerStep = 0.0;
  double dispatchesPerStep = 0.0;
};

/// Adds one World::kernelTimes() to `totals` (kernels in the order first seen).
inline void accumulateKernels(std::vector<KernelStep>& totals,
                              const std::vector<KernelTime>& times) {
  for (const KernelTime& time : times) {
    auto it = std::find_if(totals.begin(), totals.end(),
                           [&](const KernelStep& k) { return k.name == time.name; });
    if (it == totals.end()) it = totals.insert(totals.end(), KernelStep{time.name, 0.0, 0.0});
    it->millisecondsPerStep += time.milliseconds;
    it->dispatchesPerStep += time.dispatches;
  }
}

/// Turns totals over `steps` substeps into averages per substep.
inline void divideBySteps(std::vector<KernelStep>& totals, std::uint32_t steps) {
  if (steps == 0) return;
  for (KernelStep& kernel : totals) {
    kernel.millisecondsPerStep /= steps;
    kernel.dispatchesPerStep /= steps;
  }
}

}  // namespace sandphys::bench
