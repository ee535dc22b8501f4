#pragma once

#include <cstdint>

#include "sandphys/readback.h"

namespace sandphys {

/// What one World::step did. `stats` is filled only when WorldSettings::statsEachFrame is on.
struct StepReport {
  std::uint32_t substeps = 0;  ///< fixed substeps run
  float simulatedTime = 0.0f;  ///< substeps · timeStep, s
  float droppedTime = 0.0f;    ///< frame time discarded by the substep cap, s
  std::uint32_t granulesEmitted = 0;
  bool emitterBlocked = false;  ///< an emitter wanted to add granules but capacity was full
  bool hasStats = false;
  WorldStats stats{};
};

}  // namespace sandphys
