#include "scenes/pour.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes/scene.h"

namespace sandphys::scenes {

namespace {

constexpr float kPourSpeedMargin = 1.1f;
constexpr float kGuardMargin = 1.25f;
constexpr float kMinGuardSpeed = 2.0f;
// Fraction of the last granule's fall added before the sand may count as settled: after landing
// the grains still slide and bounce for a while.
constexpr double kLandingMargin = 0.5;

}  // namespace

float pourSpeed(float halfExtent, float rate, float particleDiameter) {
  const float needed = rate * kDefaultGranuleSpacing * particleDiameter /
                       static_cast<float>(emitterLayerGranules(halfExtent, particleDiameter));
  return std::max(kMinPourSpeed, kPourSpeedMargin * needed);
}

void checkPourSpeed(std::string_view scene, std::string_view widthName, float halfExtent,
                    float rate, float particleDiameter) {
  const float speed = pourSpeed(halfExtent, rate, particleDiameter);
  if (speed <= kMaxPourSpeed) return;
  throw InvalidArgument(
      std::string(scene) + ": rate " + numberText(rate) + " granules/s needs the emitter's " +
      std::to_string(emitterLayerGranules(halfExtent, particleDiameter)) + " slots to move at " +
      numberText(speed) + " m/s, more than " + numberText(kMaxPourSpeed) +
      " m/s; lower the rate or widen " + std::string(widthName));
}

float pourGuardSpeed(float speed, float height, float g) {
  const float impact = std::sqrt(speed * speed + 2.0f * g * height);
  return std::max(kMinGuardSpeed, kGuardMargin * impact);
}

kit::Course::Rule pourCourse(double fallSeconds, float settleSpeed, float maxSettleSeconds) {
  const double landing = (1.0 + kLandingMargin) * fallSeconds;
  return {.settleSpeed = settleSpeed,
          .minRestSeconds = landing,
          .maxRestSeconds = landing + maxSettleSeconds,
          .actFirst = true};
}

std::string pourStatus(const kit::Course& course, std::uint32_t poured, std::uint32_t budget) {
  if (course.acting()) return "pouring " + std::to_string(poured) + "/" + std::to_string(budget);
  if (!course.done()) return "settling";
  return course.calm() ? "settled" : "stopped";
}

}  // namespace sandphys::scenes
