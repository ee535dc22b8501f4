// The avalanche scene: sand released down a slope onto a low block with a plank standing on it,
// both simulated by Bullet and coupled through the bridge. The sand topples the plank and moves
// the low block; without the release neither moves. A block of 10 x 4 x 8 = 320 granules.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/block_avalanche.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

constexpr float kFrame = 1.0f / 60.0f;

struct Outcome {
  SceneBody low;
  SceneBody plank;
  float lowMoved = 0.0f;  // m
};

// Runs the scene for `seconds` of simulated time and prints the blocks every 0.25 s.
Outcome run(float releaseTime, double seconds) {
  BlockAvalanche scene;
  SlopeAvalanche::Config& slope = scene.slope().config();
  slope.block = {10, 4, 8};
  slope.slopeLength = 20.0f;
  slope.runoutLength = 30.0f;
  slope.releaseTime = releaseTime;
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  const std::vector<SceneBody> start = scene.bodies();
  int frame = 0;
  while (world.simulatedTime() < seconds) {
    const StepReport report = scene.step(world, kFrame);
    scene.update(world, report, world.simulatedTime());
    if (++frame % 15 == 0) {
      const std::vector<SceneBody> now = scene.bodies();
      std::printf("t %.2f s (%s): low block x %+.4f m, plank tilt %5.1f deg\n",
                  world.simulatedTime(), scene.status().c_str(),
                  now[0].position.x - start[0].position.x, now[1].tiltDegrees);
    }
  }
  const std::vector<SceneBody> end = scene.bodies();
  EXPECT_EQ(end.size(), 2u);
  Outcome outcome{end[0], end[1]};
  const Vec3 a = start[0].position, b = end[0].position;
  outcome.lowMoved = std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
  return outcome;
}

TEST(BlockAvalanche, SandTopplesThePlankAndPushesTheLowBlock) {
  const Outcome o = run(0.6f, 2.4);
  EXPECT_EQ(o.plank.name, "plank");
  EXPECT_GT(o.plank.tiltDegrees, 45.0f) << "the plank still stands";
  EXPECT_GT(o.lowMoved, 0.01f) << "the low block did not move (m)";
}

TEST(BlockAvalanche, WithoutTheReleaseNothingMoves) {
  const Outcome o = run(1e6f, 1.2);
  EXPECT_LT(o.plank.tiltDegrees, 1.0f);
  EXPECT_LT(o.lowMoved, 0.001f) << "m";
}

}  // namespace
}  // namespace sandphys::scenes
