// The paper's benchmark scene with one batch of 16,384 granules (32 x 16 x 32) settles in the
// cylinder: kinetic energy falls below a stated threshold, the largest overlap stays under d/10
// and every granule stays inside the cylinder.
//
// To fit CI (a 2-core machine without a GPU), the batch starts just above the rough floor (its
// lowest granule centres 2.5 d up: the granules reach 1.11 d from their centres) instead of 50 d
// up, and the step is larger: speed guard 2 m/s (a 2.5 d drop lands at 1 m/s) and 10 substeps per
// contact time (the accepted minimum is 8). Geometry, granules, material and contact law are the
// defaults of the paper's benchmark scene.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenes/cylinder_pile.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(CylinderPile, SixteenThousandGranulesSettle) {
  scenes::CylinderPile pile(scenes::CylinderPile::Config{.batches = 1, .firstDropHeight = 2.5f});
  WorldSettings settings = pile.settings();
  settings.maxSpeed = 2.0f;
  settings.stepsPerContact = 10.0f;
  World world(testing::gpu(), settings);
  pile.build(world);
  ASSERT_EQ(world.granulesSpawned(), 16384u);

  // Settled: mean kinetic energy per granule below that of a granule moving at 1 cm/s.
  const double granuleMass =
      tetrahedronTemplate(settings.particleDiameter, settings.material.density).mass;
  const double threshold = 16384 * 0.5 * granuleMass * 0.01 * 0.01;
  const float d = settings.particleDiameter;
  ASSERT_TRUE(settings.statsEachFrame);
  WorldStats stats;
  double maxOverlap = 0.0;
  double seconds = 0.0;
  for (; seconds < 3.0; seconds += 0.05) {
    // The statistics of each frame carry the largest overlap since the previous frame's.
    stats = world.step(0.05f).stats;
    maxOverlap = std::max(maxOverlap, stats.maxOverlap);
    if (seconds > 0.2 && stats.kineticEnergy < threshold) break;
  }
  std::printf(
      "settled after %.2f s simulated, %llu steps: KE %.3g J (threshold %.3g J), contacts %u, "
      "max overlap %.4f d, guards %llu/%llu\n",
      seconds, static_cast<unsigned long long>(stats.steps), stats.kineticEnergy, threshold,
      stats.contacts, maxOverlap / d, static_cast<unsigned long long>(stats.penetrationClamps),
      static_cast<unsigned long long>(stats.velocityClamps));
  EXPECT_LT(stats.kineticEnergy, threshold);
  EXPECT_LT(maxOverlap, 0.1 * d);
  EXPECT_EQ(stats.granulesAlive, 16384u);
  EXPECT_GT(stats.contacts, 16384u) << "a pile, resting on its granules";
  const float radius = pile.config().cylinderRadius * d;
  for (const BodyState& b : world.readBodies()) {
    if (!b.granule) continue;
    ASSERT_LT(std::hypot(b.position.x, b.position.z), radius) << "granule " << b.index;
    ASSERT_GT(b.position.y, 0.0f) << "granule " << b.index;
  }
}

}  // namespace
}  // namespace sandphys
