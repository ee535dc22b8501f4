#include "scenes/kit/course.h"

#include <algorithm>
#include <cmath>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

Course::Course(const Rule& rule, float granuleMass)
    : m_rule(rule),
      m_granuleMass(granuleMass),
      m_phase(rule.actFirst ? Phase::Acting : Phase::Settling),
      m_actStart(rule.actFirst ? 0.0 : -1.0) {}

bool Course::update(const StepReport& report, double simTime, std::uint32_t granules) {
  if (m_phase != Phase::Settling && m_phase != Phase::Resting) return false;
  const bool calm = granulesCalm(report, granules, m_granuleMass, m_rule.settleSpeed);
  const SettleWait wait = m_phase == Phase::Settling
                              ? SettleWait{m_rule.actAfter, 0.0, m_rule.maxSettleSeconds}
                              : SettleWait{m_actEnd, m_rule.minRestSeconds,
                                           m_rule.maxRestSeconds < 0.0 ? m_rule.maxSettleSeconds
                                                                       : m_rule.maxRestSeconds};
  if (!wait.over(calm, simTime)) return false;
  m_calm = calm;
  if (m_phase == Phase::Settling) {
    m_phase = Phase::Acting;
    m_actStart = simTime;
  } else {
    m_phase = Phase::Done;
  }
  return true;
}

void Course::endAct(double simTime) {
  if (m_phase != Phase::Acting) return;
  m_phase = Phase::Resting;
  m_actEnd = simTime;
}

bool granulesCalm(const StepReport& report, std::uint32_t granules, float granuleMass,
                  float settleSpeed) {
  const double settleEnergy = 0.5 * granuleMass * settleSpeed * settleSpeed;
  return report.hasStats && granules > 0 && report.stats.kineticEnergy / granules < settleEnergy;
}

double fallTime(double height, double speed, double g) {
  return (std::sqrt(speed * speed + 2.0 * g * std::max(height, 0.0)) - speed) / g;
}

}  // namespace sandphys::scenes::kit
