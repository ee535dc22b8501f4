#include "scenes/heap_metrics.h"

namespace sandphys::scenes {

void appendHeapAngleMetrics(std::vector<SceneMetric>& metrics,
                            const std::function<analysis::HeapAngle()>& measure,
                            float particleDiameter) {
  try {
    const analysis::HeapAngle heap = measure();
    metrics.push_back({"angle_of_repose_deg", heap.degrees});
    metrics.push_back({"angle_fit_r2", heap.fit.line.rSquared});
    metrics.push_back({"angle_fit_points", static_cast<double>(heap.radius.size())});
    metrics.push_back({"heap_height_d", heap.peakHeight / particleDiameter});
  } catch (const InvalidArgument&) {
    // Nothing to measure yet: the metrics leave the angle out.
  }
}

}  // namespace sandphys::scenes
