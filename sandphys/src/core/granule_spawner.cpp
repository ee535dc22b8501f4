#include "core/granule_spawner.h"

#include <cmath>
#include <numbers>

#include "core/validation.h"

namespace sandphys::detail {

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * (double(rng() >> 11) * 0x1.0p-53);
}

Quat randomOrientation(std::mt19937_64& rng) {
  const double u1 = uniform(rng, 0.0, 1.0);
  const double u2 = uniform(rng, 0.0, 2.0 * std::numbers::pi);
  const double u3 = uniform(rng, 0.0, 2.0 * std::numbers::pi);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  return {float(a * std::sin(u2)), float(a * std::cos(u2)), float(b * std::sin(u3)),
          float(b * std::cos(u3))};
}

double granuleBlockSpacing(const GranuleBlock& block, float particleDiameter) {
  require(block.countX > 0, "GranuleBlock.countX", block.countX, "must be > 0");
  require(block.countY > 0, "GranuleBlock.countY", block.countY, "must be > 0");
  require(block.countZ > 0, "GranuleBlock.countZ", block.countZ, "must be > 0");
  requireNonNegative("GranuleBlock.spacing", block.spacing, "(m)");
  require(std::isfinite(block.jitter) && block.jitter >= 0.0f && block.jitter <= 0.25f,
          "GranuleBlock.jitter", block.jitter, "must be in [0, 0.25] (units of spacing)");
  requireFinite("GranuleBlock.center.x", block.center.x);
  requireFinite("GranuleBlock.center.y", block.center.y);
  requireFinite("GranuleBlock.center.z", block.center.z);
  requireFinite("GranuleBlock.velocity.x", block.velocity.x);
  requireFinite("GranuleBlock.velocity.y", block.velocity.y);
  requireFinite("GranuleBlock.velocity.z", block.velocity.z);
  const double spacing =
      block.spacing > 0.0f ? block.spacing : kDefaultGranuleSpacing * particleDiameter;
  // A granule's particles reach d·√6/4 + d/2 = 1.1124 d from its centre; in random orientations
  // two granules closer than twice that may start overlapping.
  require(spacing * (1.0 - 2.0 * block.jitter) >= 2.0 * kGranuleReach * particleDiameter,
          "GranuleBlock.spacing", spacing,
          "less twice the jitter must be >= 2.225 particle diameters (" +
              formatValue(2.0 * kGranuleReach * particleDiameter) +
              " m), or granules start overlapping");
  return spacing;
}

std::vector<GranuleSpawn> layoutGranuleBlock(const GranuleBlock& block, float particleDiameter) {
  const double spacing = granuleBlockSpacing(block, particleDiameter);
  std::mt19937_64 rng(block.seed);
  std::vector<GranuleSpawn> spawns;
  spawns.reserve(std::size_t(block.countX) * block.countY * block.countZ);
  const double jitter = block.jitter * spacing;
  for (std::uint32_t y = 0; y < block.countY; ++y) {
    for (std::uint32_t z = 0; z < block.countZ; ++z) {
      for (std::uint32_t x = 0; x < block.countX; ++x) {
        GranuleSpawn s;
        s.position = {float(block.center.x + (x - 0.5 * (block.countX - 1)) * spacing +
                            uniform(rng, -jitter, jitter)),
                      float(block.center.y + (y - 0.5 * (block.countY - 1)) * spacing +
                            uniform(rng, -jitter, jitter)),
                      float(block.center.z + (z - 0.5 * (block.countZ - 1)) * spacing +
                            uniform(rng, -jitter, jitter))};
        s.orientation = randomOrientation(rng);
        s.velocity = block.velocity;
        spawns.push_back(s);
      }
    }
  }
  return spawns;
}

}  // namespace sandphys::detail
