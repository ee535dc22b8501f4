#pragma once

#include <functional>
#include <vector>

#include <sandphys/analysis/heap.h>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// Appends the metrics of a heap's angle of repose to `metrics`: angle_of_repose_deg,
/// angle_fit_r2, angle_fit_points (flank cells) and heap_height_d (the peak in particle diameters
/// `particleDiameter`, m), from `measure` (a scene's heapAngle). Appends none when `measure`
/// throws InvalidArgument: no heap to measure yet, as after a run stopped early.
void appendHeapAngleMetrics(std::vector<SceneMetric>& metrics,
                            const std::function<analysis::HeapAngle()>& measure,
                            float particleDiameter);

}  // namespace sandphys::scenes
