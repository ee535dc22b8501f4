#include "scenes/kit/pour.h"

#include <algorithm>
#include <cmath>

#include "scenes/kit/checks.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes::kit {

namespace {

constexpr float kPourSpeedMargin = 1.1f;
// Fraction of the last granule's fall added before the sand may count as settled: after landing
// the grains still slide and bounce for a while.
constexpr double kLandingMargin = 0.5;
// Depth of the sink's top below the floor's particle centres, d: past the floor's edge a grain
// that deep has left.
constexpr float kSinkDepth = 3.0f;

}  // namespace

float Pour::speed() const {
  const float needed =
      rate * kDefaultGranuleSpacing * d / static_cast<float>(emitterLayerGranules(halfExtent(), d));
  return std::max(kMinPourSpeed, kPourSpeedMargin * needed);
}

float Pour::guardSpeed() const {
  return pourGuardSpeed(speed(), height * d, kGravity);
}

double Pour::landingSeconds(double g) const {
  return (1.0 + kLandingMargin) * fallTime(height * d, speed(), g);
}

void Pour::checkSpeed(std::string_view scene, std::string_view widthName) const {
  require(speed() <= kMaxPourSpeed, scene, "rate ", rate, " granules/s needs the emitter's ",
          emitterLayerGranules(halfExtent(), d), " slots to move at ", speed(), " m/s, more than ",
          kMaxPourSpeed, " m/s; lower the rate or widen ", widthName);
}

void Pour::checkAboveFloor(std::string_view scene) const {
  require(height >= 2.0f * kReach, scene, "pour-height ", height,
          " d leaves no room for a granule above the floor (at least ", 2.0f * kReach, " d)");
  checkSpeed(scene, "the outlet");
}

EmitterSettings Pour::emitter(float x, std::uint64_t seed) const {
  return {.center = {x, height * d, 0.0f},
          .halfExtentX = halfExtent(),
          .halfExtentZ = halfExtent(),
          .rate = rate,
          .velocity = {0.0f, -speed(), 0.0f},
          .maxGranules = granules,
          .seed = seed};
}

Sink Pour::sink(float floorHalfExtent) const {
  const float wide = floorHalfExtent + height * d;
  return {.min = {-wide, -(kSinkDepth + 10.0f) * d, -wide}, .max = {wide, -kSinkDepth * d, wide}};
}

Course::Rule Pour::course(float settleSpeed, float maxSettleSeconds, double g) const {
  return {.settleSpeed = settleSpeed,
          .minRestSeconds = landingSeconds(g),
          .maxRestSeconds = landingSeconds(g) + maxSettleSeconds,
          .actFirst = true};
}

SceneBounds Pour::bounds(float halfX, float halfZ) const {
  return {{-halfX, -kSinkDepth * d, -halfZ}, {halfX, (height + 1.0f) * d, halfZ}};
}

void PourCourse::count(const World& world, double simTime) {
  m_poured = world.granulesSpawned() - m_before;
  if (acting() && m_poured >= m_budget) endAct(simTime);
}

std::string PourCourse::status() const {
  if (acting()) return "pouring " + std::to_string(m_poured) + "/" + std::to_string(m_budget);
  if (!done()) return "settling";
  return calm() ? "settled" : "stopped";
}

std::uint32_t emitterLayerGranules(float halfExtent, float particleDiameter) {
  return static_cast<std::uint32_t>(emitterLayerSlots(
      EmitterSettings{.halfExtentX = halfExtent, .halfExtentZ = halfExtent}, particleDiameter));
}

}  // namespace sandphys::scenes::kit
