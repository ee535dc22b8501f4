#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <sandphys/sandphys.h>

#include "scenes/kit/course.h"

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

/// The course of a pour (repose-heap, dunes): the pour is the act, from the first frame until
/// the scene ends it; then the last granule falls (fallSeconds, with a margin for the grains to
/// slide and bounce) and the sand is calm or maxSettleSeconds more have passed.
kit::Course::Rule pourCourse(double fallSeconds, float settleSpeed, float maxSettleSeconds);

/// "pouring n/N", "settling", "settled" (calm) or "stopped" (the wait ran out) for a pour of
/// `budget` granules that has poured `poured` so far.
std::string pourStatus(const kit::Course& course, std::uint32_t poured, std::uint32_t budget);

}  // namespace sandphys::scenes
