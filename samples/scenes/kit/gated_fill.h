#pragma once

#include <cstdint>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/kit/course.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes::kit {

// A fill behind a gate (hourglass, repose-scupper): a loose lattice settles behind the gate, the
// gate opens, and the sand flows. Their Configs share the fields these read.

/// Room between a fill granule at its farthest jitter and the walls and the gate, d.
inline constexpr float kFillClearance = 0.2f;

/// The blocks of a loose fill of `granules` as a scene lays them out: each block added takes the
/// next seed of the fill's stream (seed · 1000003 + the block's index) and its granules from
/// those left.
class FillBlocks {
 public:
  FillBlocks(std::uint32_t granules, std::uint64_t seed)
      : m_left(granules), m_seed(seed * 1000003u) {}

  /// Granules of the fill not yet in a block.
  std::uint32_t left() const { return m_left; }
  /// Adds `block` (at most left() granules) with the next seed of the stream.
  void add(GranuleBlock block) {
    block.seed = m_seed + m_blocks.size();
    m_left -= block.countX * block.countY * block.countZ;
    m_blocks.push_back(block);
  }
  /// The blocks in the order added, which is the order of adds to the World.
  const std::vector<GranuleBlock>& blocks() const { return m_blocks; }

 private:
  std::uint32_t m_left;
  std::uint64_t m_seed;
  std::vector<GranuleBlock> m_blocks;
};

/// The walls' and the gate's surface: wallFriction whatever the grains' μ, as the paper's
/// containers have.
template <class Config>
SurfaceMaterial wallMaterial(const Config& c) {
  return {.friction = c.wallFriction, .restitution = c.restitution};
}

/// The settings rule of a gated fill of `granules` whose grains fall at most `fall` (m): the
/// grains' material and substeps from the config; the default per-frame statistics serve the
/// settle tests and the count left.
template <class Config>
SettingsRule gatedFillRule(const Config& c, std::uint64_t granules, float fall) {
  return {.granules = granules,
          .maxSpeed = pourGuardSpeed(0.0f, fall, kGravity),
          .stepsPerContact = c.stepsPerContact,
          .youngsModulus = c.youngsModulus,
          .friction = c.friction,
          .restitution = c.restitution};
}

/// The course of a gated fill in a World made from `settings`: the gate opens once the fill has
/// settled, releaseTime at the earliest; then the sand rests `minRest` to `maxRest` s (the
/// Course::Rule's minRestSeconds and maxRestSeconds).
template <class Config>
Course gateCourse(const Config& c, const WorldSettings& settings, double minRest = 0.0,
                  double maxRest = -1.0) {
  return Course({.settleSpeed = c.settleSpeed,
                 .maxSettleSeconds = c.maxSettleSeconds,
                 .actAfter = c.releaseTime,
                 .minRestSeconds = minRest,
                 .maxRestSeconds = maxRest},
                granuleMass(settings));
}

/// Height between two layers of a loose starting lattice of granules (hourglass, repose-scupper),
/// d. Odd layers are shifted by half the lattice spacing along x and z, so a granule sits over the
/// gap between four below it: centres of neighbouring layers are then sqrt(2 (1.2 d)² + v²) apart,
/// which for v = 1.85 d leaves 2.225 d (the distance at which two granules of any orientation
/// cannot touch) after both move by their largest jitter of 0.072 d along each axis. A denser
/// start than the 2.4 d cubic lattice settles sooner.
inline constexpr float kShiftedLayerHeight = 1.85f;

}  // namespace sandphys::scenes::kit
