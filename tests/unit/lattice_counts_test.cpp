// The counts a scene sizes its World with, from the library that places the particles: they must
// match what World::addRoughFloor and an emitter really build (tests/scenes and tests/gl check
// the World's side), and stay cheap and exact for sizes no World could hold.
#include <gtest/gtest.h>

#include <sandphys/sandphys.h>

namespace sandphys {
namespace {

TEST(RoughFloorParticles, CountsTheLatticePointsInTheDiscOrTheRectangle) {
  // Lattice points with i² + j² <= 50² (Gauss's circle problem): 7845, close to π·50² = 7854.
  EXPECT_EQ(roughFloorParticles(RoughFloor{.radius = 1.0f}, 0.02f), 7845u);
  EXPECT_EQ(roughFloorParticles(RoughFloor{.radius = 0.05f}, 0.02f), 21u);  // 5 × 5 less corners
  EXPECT_EQ(roughFloorParticles(RoughFloor{.radius = 0.01f}, 0.02f), 1u);
  // A rectangle: 2 floor(h / s) + 1 points along each side; a spacing of its own overrides d.
  EXPECT_EQ(roughFloorParticles(RoughFloor{.halfExtentX = 0.05f, .halfExtentZ = 0.1f}, 0.02f),
            5u * 11u);
  EXPECT_EQ(roughFloorParticles(
                RoughFloor{.halfExtentX = 0.05f, .halfExtentZ = 0.1f, .spacing = 0.05f}, 0.02f),
            3u * 5u);
}

TEST(RoughFloorParticles, APointOnTheEdgeCountsThoughTheFloatExtentFallsShortOfIt) {
  // 0.9f / 0.02f is 44.9999998 in double: 45 d asked for, 45 columns each side still built.
  const float d = 0.02f;
  EXPECT_EQ(roughFloorParticles(RoughFloor{.halfExtentX = 45 * d, .halfExtentZ = 0.5f * d}, d),
            91u * 1u);
  // So does a disc whose float radius falls short of 45 spacings: i² + j² <= 45².
  EXPECT_EQ(roughFloorParticles(RoughFloor{.radius = 45 * d}, d), 6361u);
  // Well short of the next point, nothing is added.
  EXPECT_EQ(roughFloorParticles(RoughFloor{.halfExtentX = 44.99f * d, .halfExtentZ = 0.5f * d}, d),
            89u);
}

TEST(RoughFloorParticles, AFloorBeyondAnyWorldIsCountedWithoutBuildingIt) {
  // 10^5 points a side: 10^10 particles, more than 2^32, counted row by row.
  const std::uint64_t rows = 2 * 50000 + 1;
  EXPECT_EQ(roughFloorParticles(RoughFloor{.halfExtentX = 500.0f, .halfExtentZ = 500.0f}, 0.01f),
            rows * rows);
}

TEST(EmitterLayerSlots, ASlotEveryGranuleSpacingEdgesIncluded) {
  const float d = 0.02f;
  const float spacing = kDefaultGranuleSpacing * d;
  // Half extent of two spacings plus a little: five slots along x; one spacing: three along z.
  const EmitterSettings emitter{.halfExtentX = 2.05f * spacing, .halfExtentZ = 1.05f * spacing};
  EXPECT_EQ(emitterLayerSlots(emitter, d), 5u * 3u);
  // Narrower than a spacing: a single slot.
  EXPECT_EQ(emitterLayerSlots(
                EmitterSettings{.halfExtentX = 0.1f * spacing, .halfExtentZ = 0.1f * spacing}, d),
            1u);
}

}  // namespace
}  // namespace sandphys
