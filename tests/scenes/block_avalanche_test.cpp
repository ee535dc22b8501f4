// The avalanche scene: sand released down a slope onto a low block with a plank standing on it,
// both simulated by Bullet and coupled through the bridge. While the wall holds the sand (the
// first 0.6 s: the blocks stand on Bullet's floor, coupled, with no sand released) neither block
// moves; once it is released the sand topples the plank and moves the low block. The scene as it
// ships (1008 granules): a smaller block toppled the plank on only some trajectories, which any
// change of last bits (a sort of the granules at another interval) picks among.
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
  // The same at the release, while no sand had been let go.
  float plankTiltHeld = -1.0f;  // deg
  float lowMovedHeld = -1.0f;   // m
};

float distance(const Vec3& a, const Vec3& b) {
  return std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
}

// Runs the scene for `seconds` of simulated time and prints the blocks every 0.25 s.
Outcome run(float releaseTime, double seconds) {
  BlockAvalanche scene;
  scene.config().releaseTime = releaseTime;
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  const std::vector<SceneBody> start = scene.bodies(world);
  Outcome outcome;
  int frame = 0;
  while (world.simulatedTime() < seconds) {
    const StepReport report = scene.step(world, kFrame);
    if (!scene.released()) {
      const std::vector<SceneBody> held = scene.bodies(world);
      outcome.plankTiltHeld = held[1].tiltDegrees;
      outcome.lowMovedHeld = distance(start[0].position, held[0].position);
    }
    scene.update(world, report, world.simulatedTime());
    if (++frame % 15 == 0) {
      const std::vector<SceneBody> now = scene.bodies(world);
      std::printf("t %.2f s (%s): low block x %+.4f m, plank tilt %5.1f deg\n",
                  world.simulatedTime(), scene.status().c_str(),
                  now[0].position.x - start[0].position.x, now[1].tiltDegrees);
    }
  }
  const std::vector<SceneBody> end = scene.bodies(world);
  EXPECT_EQ(end.size(), 2u);
  if (end.size() < 2u) return outcome;  // the checks on the outcome then fail, not a crash
  outcome.low = end[0];
  outcome.plank = end[1];
  outcome.lowMoved = distance(start[0].position, end[0].position);
  return outcome;
}

TEST(BlockAvalanche, SandTopplesThePlankAndPushesTheLowBlock) {
  const Outcome o = run(0.6f, 2.2);
  ASSERT_GE(o.plankTiltHeld, 0.0f) << "no frame before the release";
  EXPECT_LT(o.plankTiltHeld, 1.0f) << "the plank moved before any sand was let go";
  EXPECT_LT(o.lowMovedHeld, 0.001f) << "the low block moved before any sand was let go (m)";
  EXPECT_EQ(o.plank.name, "plank");
  EXPECT_GT(o.plank.tiltDegrees, 45.0f) << "the plank still stands";
  EXPECT_GT(o.lowMoved, 0.01f) << "the low block did not move (m)";
}

}  // namespace
}  // namespace sandphys::scenes
