#pragma once

// A scene's metric by its name, for the scenes' tests. Header only, as every_scene.h: it needs
// the samples' scenes (sandphys_scenes), which sandphys_testing does not link.
#include <gtest/gtest.h>

#include <limits>
#include <span>
#include <string_view>

#include "scenes/scene.h"

namespace sandphys::testing {

/// The value of the metric called `name`; a metric the scene does not report fails the test (and
/// is NaN, which no comparison accepts).
inline double metricNamed(std::span<const scenes::SceneMetric> metrics, std::string_view name) {
  for (const scenes::SceneMetric& metric : metrics) {
    if (metric.name == name) return metric.value;
  }
  ADD_FAILURE() << "no metric " << name;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace sandphys::testing
