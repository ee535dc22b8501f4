#pragma once

#include <cstdint>

#include "sandphys/settings.h"

namespace sandphys {

/// SleepSettings resolved for a World (the defaults taken from d and g), as the shaders use them
/// (docs/architecture.md, "sleep").
struct SleepModel {
  bool enabled = false;
  float linearSpeed = 0.0f;       ///< m/s
  float angularSpeed = 0.0f;      ///< rad/s
  float time = 0.0f;              ///< s
  float wakeAcceleration = 0.0f;  ///< m/s²
  /// Substeps below both thresholds before sleep: ceil(time / timeStep), at least 1.
  std::uint32_t substeps = 0;
  /// How far a body's calm count may run ahead of the smallest count of the bodies it touches:
  /// ceil(substeps / kSleepContacts).
  std::uint32_t neighbourLead = 0;

  /// Resolves and validates settings.sleep for the substep `timeStep` (s); throws
  /// InvalidArgument naming the field, value and limit.
  static SleepModel fromSettings(const WorldSettings& settings, float timeStep);
};

}  // namespace sandphys
