#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <sandphys/sandphys.h>

namespace sandphys::scenes {

/// A steady pour from a square emitter above a floor, as the pouring scenes (sand-box-pour,
/// repose-heap, dunes) set it up: the emitter's speed for a rate, the fastest speed a pour may
/// have, and the speed guard for grains that leave it and fall.

/// Slowest emitter, m/s: a fresh layer has to clear the square before the next one starts.
inline constexpr float kMinPourSpeed = 0.5f;
/// Fastest emitter a scene accepts, m/s: beyond it the impacts overlap the grains by well over
/// the d/10 that the penetration guard allows; a wider emitter takes the rate more gently.
inline constexpr float kMaxPourSpeed = 3.0f;

/// Speed of a square emitter of half extent `halfExtent` (m) that pours `rate` granules/s of
/// particles `particleDiameter` (m) wide: its layer of emitterLayerGranules() slots leaves every
/// spacing / speed seconds, with a margin so that float rounding never makes EmitterSettings
/// refuse the rate; at least kMinPourSpeed.
float pourSpeed(float halfExtent, float rate, float particleDiameter);

/// Throws InvalidArgument "`scene`: rate R granules/s needs the emitter's n slots to move at
/// v m/s, more than 3 m/s; lower the rate or widen `widthName`" when pourSpeed is over
/// kMaxPourSpeed.
void checkPourSpeed(std::string_view scene, std::string_view widthName, float halfExtent,
                    float rate, float particleDiameter);

/// Speed guard (WorldSettings::maxSpeed) for grains that leave an emitter at `speed` (m/s) and
/// fall `height` (m) under gravity `g` (m/s²): the impact with a margin for rebounds and the rim
/// speed of spinning grains, and at least 2 m/s.
float pourGuardSpeed(float speed, float height, float g);

/// When a pour has ended and the sand it made has settled (repose-heap, dunes): the last granule
/// leaves the emitter, falls (fallTime with a margin for the grains to slide and bounce), and
/// then the sand is calm (granulesCalm) or maxSettleSeconds more have passed.
class PourSettling {
 public:
  /// `fallSeconds`: the fall of the last granule from the emitter onto the floor, s.
  PourSettling(double fallSeconds, float granuleMass, float settleSpeed, float maxSettleSeconds)
      : m_fallSeconds(fallSeconds),
        m_granuleMass(granuleMass),
        m_settleSpeed(settleSpeed),
        m_maxSettleSeconds(maxSettleSeconds) {}

  /// After each frame: `poured` granules so far of the pour's `budget`, `report` the frame's
  /// step (its stats tell the kinetic energy). True from the frame the sand has settled on.
  bool update(const StepReport& report, double simTime, std::uint32_t poured, std::uint32_t budget);
  /// Simulated time at which the last granule was poured, s; negative while pouring.
  double pourEnd() const { return m_pourEnd; }
  /// The wait is over: the sand is calm, or maxSettleSeconds ran out.
  bool settled() const { return m_settled; }
  /// The sand was calm when the wait ended (false when it ran out with the sand still moving).
  bool calm() const { return m_calm; }
  /// "pouring n/N", "settling", "settled" or "stopped" (the wait ran out).
  std::string status(std::uint32_t poured, std::uint32_t budget) const;

 private:
  double m_fallSeconds;
  float m_granuleMass;
  float m_settleSpeed;
  float m_maxSettleSeconds;
  double m_pourEnd = -1.0;
  bool m_settled = false;
  bool m_calm = false;
};

}  // namespace sandphys::scenes
