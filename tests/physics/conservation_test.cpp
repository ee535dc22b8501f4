// Nothing is lost: a closed box keeps every granule; a sink removes granules and counts them, so
// that granules alive = spawned - killed.
#include <gtest/gtest.h>

#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(Conservation, ClosedBoxLosesNoGranule) {
  testing::TestWorld w(testing::smallSettings(400));
  const Box box{.center = {0, 0.2f, 0}, .halfExtents = {0.08f, 0.2f, 0.08f}, .inside = true};
  w->addCollider(box);
  w->addGranules(GranuleBlock{.center = {0, 0.2f, 0},
                              .countX = 5,
                              .countY = 12,
                              .countZ = 5,
                              .velocity = {0.5f, -1.0f, 0.3f}});
  w.simulate(0.25);
  WorldStats stats = w->readStats();
  EXPECT_EQ(stats.granulesAlive, 300u);
  EXPECT_EQ(stats.granulesKilled, 0u);
  const float margin = 0.5f * w->settings().particleDiameter;
  for (const auto& p : w->readParticles()) {
    EXPECT_LT(std::abs(p.position.x), box.halfExtents.x + margin);
    EXPECT_LT(std::abs(p.position.z), box.halfExtents.z + margin);
    EXPECT_GT(p.position.y, -margin);
  }
  EXPECT_GT(stats.contacts, 300u);
}

TEST(Conservation, SinkRemovesAndCountsGranules) {
  testing::TestWorld w(testing::smallSettings(300));
  // A funnel over a sink: what drains through the outlet is removed.
  const float d = w->settings().particleDiameter;
  w->addCollider(Funnel{
      .outletCenter = {0, 0.2f, 0}, .outletRadius = 4 * d, .halfAngle = 0.785f, .height = 0.3f});
  w->addSink(Sink{.min = {-1, -1, -1}, .max = {1, 0.05f, 1}});
  w->addGranules(GranuleBlock{.center = {0, 0.35f, 0}, .countX = 5, .countY = 8, .countZ = 5});
  w.simulate(0.6);
  WorldStats stats = w->readStats();
  EXPECT_GT(stats.granulesKilled, 10u) << "granules drained through the outlet";
  EXPECT_EQ(stats.granulesAlive + stats.granulesKilled, stats.granulesSpawned);
  std::uint32_t alive = 0;
  for (const auto& b : w->readBodies()) {
    alive += b.alive;
    if (b.alive) {
      EXPECT_GT(b.position.y, 0.05f);
    }
  }
  EXPECT_EQ(alive, stats.granulesAlive);
}

}  // namespace
}  // namespace sandphys
