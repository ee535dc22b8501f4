// Emitters add granules at their rate, within their budget and the world's fixed capacity.
#include <gtest/gtest.h>

#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(Emitter, AddsGranulesAtItsRateWithoutOverlaps) {
  // No floor: the only way two granules could touch is an emitter placing one inside another.
  testing::TestWorld w(testing::smallSettings(1000));
  w->addEmitter(EmitterSettings{.center = {0, 0.5f, 0},
                                .halfExtentX = 0.1f,
                                .halfExtentZ = 0.1f,
                                .rate = 400.0f,
                                .velocity = {0, -1.0f, 0}});
  w.simulate(0.25);
  const std::uint32_t spawned = w->granulesSpawned();
  EXPECT_NEAR(double(spawned), 400.0 * 0.25, 2.0);
  WorldStats stats = w->readStats();
  EXPECT_EQ(stats.granulesAlive, spawned);
  // New granules never start inside older ones.
  EXPECT_EQ(stats.maxOverlap, 0.0);
  EXPECT_EQ(stats.contacts, 0u);
}

TEST(Emitter, LetsNoGranuleBeBornWherePlaceIsTaken) {
  // A static granule sits in the emitter's plane, where some of its first granules would appear:
  // those are not born (dead from the start, counted), the others fall past it untouched.
  WorldSettings s = testing::smallSettings(1000);
  s.gravity = {0.0f, 0.0f, 0.0f};
  testing::TestWorld w(s);
  w->addBody(tetrahedronTemplate(s.particleDiameter, s.material.density),
             {.position = {0.0f, 0.5f, 0.0f}, .motion = Motion::Static});
  // A body far from everything, where the never-written state of a granule not born would
  // stand (zeroed memory: the origin): it must feel nothing.
  const BodyId sentinel = w.addGranule({0.0f, 0.0f, 0.0f});
  w->substep(1);  // a grid to check the places against
  w->addEmitter(EmitterSettings{.center = {0, 0.5f, 0},
                                .halfExtentX = 0.1f,
                                .halfExtentZ = 0.1f,
                                .rate = 400.0f,
                                .velocity = {0, -1.0f, 0},
                                .maxGranules = 40});
  w.simulate(0.15);
  const WorldStats stats = w->readStats();
  EXPECT_EQ(w->granulesSpawned(), 40u);
  EXPECT_GE(stats.granulesNotBorn, 1u) << "a granule was born inside the one in its way";
  EXPECT_LE(stats.granulesNotBorn, 8u) << "granules clear of the obstacle were refused too";
  EXPECT_EQ(stats.granulesAlive, 40u - stats.granulesNotBorn);
  // Nothing that was born started inside anything.
  EXPECT_LT(stats.maxOverlap, 0.01 * w->settings().particleDiameter);
  const BodyState still = w->readBody(sentinel);
  EXPECT_EQ(still.position.x, 0.0f);
  EXPECT_EQ(still.position.y, 0.0f);
  EXPECT_EQ(still.position.z, 0.0f);
  EXPECT_EQ(still.velocity.y, 0.0f);
}

TEST(Emitter, RefusesARateItsLatticeCannotTake) {
  testing::TestWorld w;
  try {
    // 3 x 3 slots every 0.048 s at 1 m/s: at most 187 granules/s.
    w->addEmitter(EmitterSettings{.halfExtentX = 0.05f, .halfExtentZ = 0.05f, .rate = 400.0f});
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("EmitterSettings.rate = 400 is invalid: must be <= 187"),
              std::string::npos)
        << e.what();
  }
}

TEST(Emitter, StopsAtItsBudgetAndAtCapacity) {
  testing::TestWorld w(testing::smallSettings(30));
  w->addEmitter(EmitterSettings{.center = {0, 0.5f, 0},
                                .halfExtentX = 0.1f,
                                .halfExtentZ = 0.1f,
                                .rate = 200.0f,
                                .maxGranules = 20});
  w.simulate(0.15);
  EXPECT_EQ(w->granulesSpawned(), 20u);
  w->addEmitter(EmitterSettings{
      .center = {0, 0.8f, 0}, .halfExtentX = 0.1f, .halfExtentZ = 0.1f, .rate = 500.0f, .seed = 2});
  StepReport report = w->step(0.1f);
  EXPECT_EQ(w->bodyCount(), 30u);
  EXPECT_TRUE(report.emitterBlocked);
  EXPECT_EQ(w->bodyCapacity(), 30u) << "step() never grows capacity";
}

}  // namespace
}  // namespace sandphys
