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

}  // namespace sandphys::scenes
