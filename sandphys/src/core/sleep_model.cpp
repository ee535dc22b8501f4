#include "sandphys/sleep_model.h"

#include <algorithm>
#include <cmath>

#include "core/validation.h"
#include "core/world_checks.h"

namespace sandphys {

SleepModel SleepModel::fromSettings(const WorldSettings& s, float timeStep) {
  using detail::require;
  const SleepSettings& sleep = s.sleep;
  detail::checkSettingRanges(s);
  SleepModel m;
  if (!sleep.enabled) return m;
  require(s.contactLaw == ContactLaw::HertzMindlin, "WorldSettings.contactLaw",
          double(unsigned(s.contactLaw)),
          "must be ContactLaw::HertzMindlin (0) with WorldSettings.sleep.enabled: the paper's law "
          "has no static friction, so its sand never comes to rest");
  const double d = s.particleDiameter;
  const double g = std::sqrt(double(s.gravity.x) * s.gravity.x + double(s.gravity.y) * s.gravity.y +
                             double(s.gravity.z) * s.gravity.z);
  const bool derived = sleep.linearSpeed == 0.0f || sleep.angularSpeed == 0.0f ||
                       sleep.time == 0.0f || sleep.wakeAcceleration == 0.0f;
  require(!derived || g > 0.0, "|WorldSettings.gravity|", g,
          "must be > 0 for the derived defaults of WorldSettings.sleep (set linearSpeed, "
          "angularSpeed, time and wakeAcceleration when there is no gravity)");
  auto pick = [](float given, double derivedValue) {
    return given > 0.0f ? given : static_cast<float>(derivedValue);
  };
  m.enabled = true;
  m.linearSpeed = pick(sleep.linearSpeed, kSleepLinearSpeed * std::sqrt(g * d));
  m.angularSpeed = pick(sleep.angularSpeed, kSleepAngularSpeed * std::sqrt(g / d));
  m.time = pick(sleep.time, kSleepTime * std::sqrt(d / g));
  m.wakeAcceleration = pick(sleep.wakeAcceleration, kSleepWakeAcceleration * g);
  const double substeps = std::ceil(double(m.time) / timeStep);
  // The count saturates at `substeps` in 31 bits (the top bit is free for the shaders).
  require(substeps < double(1u << 30), "WorldSettings.sleep.time", m.time,
          "must be < 2^30 substeps of " + detail::formatValue(timeStep) + " s");
  m.substeps = static_cast<std::uint32_t>(std::max(substeps, 1.0));
  m.neighbourLead = (m.substeps + kSleepContacts - 1) / kSleepContacts;
  return m;
}

}  // namespace sandphys
