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

bool PourSettling::update(const StepReport& report, double simTime, std::uint32_t poured,
                          std::uint32_t budget) {
  if (m_settled) return true;
  if (poured < budget) return false;
  if (m_pourEnd < 0.0) m_pourEnd = simTime;
  const double sincePour = simTime - m_pourEnd;
  const double landing = (1.0 + kLandingMargin) * m_fallSeconds;
  if (sincePour < landing) return false;
  const std::uint32_t alive = report.hasStats ? report.stats.granulesAlive : poured;
  m_calm = granulesCalm(report, alive, m_granuleMass, m_settleSpeed);
  m_settled = m_calm || sincePour >= landing + m_maxSettleSeconds;
  return m_settled;
}

std::string PourSettling::status(std::uint32_t poured, std::uint32_t budget) const {
  if (m_pourEnd < 0.0) return "pouring " + std::to_string(poured) + "/" + std::to_string(budget);
  if (!m_settled) return "settling";
  return m_calm ? "settled" : "stopped";
}

}  // namespace sandphys::scenes
