#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "sandphys/math.h"
#include "sandphys/spawn.h"

namespace sandphys::detail {

/// Pose and velocity of one granule about to be added.
struct GranuleSpawn {
  Vec3 position;
  Quat orientation;
  Vec3 velocity;
};

/// A uniformly distributed random orientation (Shoemake's method).
Quat randomOrientation(std::mt19937_64& rng);
/// A uniform number in [lo, hi) from the generator's raw bits (the same on every platform,
/// unlike std::uniform_real_distribution).
double uniform(std::mt19937_64& rng, double lo, double hi);

/// Validates a GranuleBlock (InvalidArgument names the field) and returns its lattice spacing, m.
double granuleBlockSpacing(const GranuleBlock& block, float particleDiameter);

/// Granule poses of a GranuleBlock; validates it (InvalidArgument names the field).
std::vector<GranuleSpawn> layoutGranuleBlock(const GranuleBlock& block, float particleDiameter);

}  // namespace sandphys::detail
