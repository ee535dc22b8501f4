#pragma once

#include <cstdint>

#include "sandphys/math.h"

namespace sandphys {

/// Default granule lattice spacing in particle diameters: about the paper's two diameters, plus
/// the room that random orientations need so that no two granules start overlapping.
inline constexpr float kDefaultGranuleSpacing = 2.4f;

/// Distance from a tetrahedral granule's centre to the far side of its farthest particle, in
/// particle diameters: the circumradius √6/4 of a unit tetrahedron plus a particle's radius.
inline constexpr double kGranuleReach = 0.6123724356957945 + 0.5;

/// A block of granules on a lattice, each with a small random offset and a random orientation.
struct GranuleBlock {
  Vec3 center{};             ///< centre of the block, m
  std::uint32_t countX = 8;  ///< granules along x; > 0
  std::uint32_t countY = 8;  ///< granules along y; > 0
  std::uint32_t countZ = 8;  ///< granules along z; > 0
  /// Lattice spacing, m; 0 means kDefaultGranuleSpacing particle diameters. Must leave room for
  /// any orientation: spacing · (1 - 2 jitter) >= 2.225 d (else InvalidArgument).
  float spacing = 0.0f;
  float jitter = 0.03f;    ///< random offset per axis, in units of spacing; [0, 0.25]
  Vec3 velocity{};         ///< initial velocity of every granule, m/s
  std::uint64_t seed = 1;  ///< same seed, same block
};

/// Adds granules over time from a horizontal rectangle, moving with `velocity` (which should
/// carry them out of the rectangle; downward by default). The emitter's budget is fixed at
/// creation; it stops at the budget or when the world's capacity is full.
struct EmitterSettings {
  Vec3 center{};                            ///< centre of the emitting rectangle, m
  float halfExtentX = 0.1f;                 ///< m, > 0
  float halfExtentZ = 0.1f;                 ///< m, > 0
  float rate = 1000.0f;                     ///< granules per second, > 0
  Vec3 velocity{0.0f, -1.0f, 0.0f};         ///< initial velocity, m/s; non-zero
  std::uint32_t maxGranules = 0xffffffffu;  ///< total budget of this emitter
  std::uint64_t seed = 1;
};

/// Slots in one layer of `emitter`'s lattice in a World of particles `particleDiameter` (m) wide:
/// a slot every kDefaultGranuleSpacing diameters across the rectangle, edges included. A layer
/// leaves every spacing / speed seconds, so this bounds the rate an emitter can pour.
std::uint64_t emitterLayerSlots(const EmitterSettings& emitter, float particleDiameter);

}  // namespace sandphys
