// The dunes scene at CI size: sand poured in two columns 24 d apart (300 granules each, from
// 12 d up) settles into a dune with a crest over each column and a saddle between them. The
// columns stand further apart than a heap's foot is wide (about 13 d at this size): closer, the
// two heaps merge into one mound whose crests move towards each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "scenes/dunes.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

constexpr float kFrame = 1.0f / 60.0f;
constexpr double kLongestRun = 6.0;

TEST(Dunes, TwoColumnsMakeTwoCrestsWithASaddleBetween) {
  Dunes::Config config;
  config.granules = 300;
  config.separation = 24.0f;
  config.pourHeight = 12.0f;
  config.floorHalfLength = 32.0f;
  config.floorHalfWidth = 14.0f;
  config.stepsPerContact = kMinStepsPerContact;
  Dunes scene(config);
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  runUntilFinished(scene, world, kFrame, kLongestRun);
  ASSERT_TRUE(scene.finished()) << scene.status();
  const Dunes::Profile p = scene.profile(world.readBodies());
  const double d = config.particleDiameter;
  std::printf("crests %.2f d at x %.1f d and %.2f d at x %.1f d; saddle %.2f d at x %.1f d\n",
              p.leftCrest[1] / d, p.leftCrest[0] / d, p.rightCrest[1] / d, p.rightCrest[0] / d,
              p.saddle[1] / d, p.saddle[0] / d);
  // Each crest stands over its column (within a few d), the saddle between them, and at least a
  // diameter lower than the lower crest.
  EXPECT_NEAR(p.leftCrest[0] / d, -12.0, 4.0);
  EXPECT_NEAR(p.rightCrest[0] / d, 12.0, 4.0);
  EXPECT_GT(p.saddle[0], p.leftCrest[0]);
  EXPECT_LT(p.saddle[0], p.rightCrest[0]);
  EXPECT_LT(p.saddle[1] + d, std::min(p.leftCrest[1], p.rightCrest[1]));
  EXPECT_GT(p.saddle[1], 0.0) << "the two heaps meet: sand lies between the crests";
  // Nearly all the sand stays on the floor.
  std::uint32_t onFloor = 0;
  for (const BodyState& b : world.readBodies()) onFloor += b.granule && scene.contains(b.position);
  EXPECT_GT(onFloor, 570u);
}

}  // namespace
}  // namespace sandphys::scenes
