// The slope-avalanche scene on a real (headless) World: the retaining wall holds the block, and
// once it is removed the sand runs down a 30 degree slope but not across a flat floor. A block of
// 6 x 3 x 4 = 72 granules on a short slope keeps each test to seconds on llvmpipe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/kit/readback.h"
#include "scenes/slope_avalanche.h"
#include "support/scene_metric.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

using testing::metricNamed;

constexpr float kFrame = 1.0f / 60.0f;

SlopeAvalanche::Config smallSlope(float angle, float releaseTime) {
  return {.slopeAngle = angle,
          .block = {6, 3, 4},
          .friction = 0.3f,
          .releaseTime = releaseTime,
          .slopeLength = 20.0f,
          .runoutLength = 20.0f};
}

// The lattice the block starts on collapses and creeps against the wall for about 0.5 s (its
// kinetic energy per granule falls below that of 5 cm/s at about 0.55 s, and the centre of mass
// moves 0.15 d from 0.6 s to 1 s), so "settled" is taken at 0.6 s and the wall goes at 0.8 s.
constexpr double kSettled = 0.6;
constexpr float kRelease = 0.8f;

// Runs a scene and keeps the granules at three moments: once the block has settled behind the
// wall (`settledAt`), just before the wall goes (or at the end without a release) and
// `afterRelease` seconds after it.
struct AvalancheRun {
  std::vector<BodyState> settled;
  std::vector<BodyState> beforeRelease;
  std::vector<BodyState> end;
  double releasedAt = -1.0;
};

AvalancheRun run(SlopeAvalanche& scene, double settledAt, double afterRelease, double limit) {
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  AvalancheRun result;
  while (world.simulatedTime() < limit) {
    const StepReport report = world.step(kFrame);
    const double t = world.simulatedTime();
    if (result.settled.empty() && t >= settledAt) result.settled = world.readBodies();
    // The scene may remove the wall in any frame from its release time on.
    if (!scene.released() && t >= scene.config().releaseTime) {
      result.beforeRelease = world.readBodies();
    }
    scene.update(world, report, t);
    if (scene.released() && result.releasedAt < 0.0) result.releasedAt = scene.releasedAt();
    if (scene.released() && t >= result.releasedAt + afterRelease) break;
  }
  if (result.beforeRelease.empty()) result.beforeRelease = world.readBodies();
  result.end = world.readBodies();
  for (const BodyState& body : result.end) {
    EXPECT_TRUE(scene.contains(body.position))
        << "granule " << body.id.index << " left the channel";
  }
  return result;
}

TEST(SlopeAvalanche, HeldBlockStaysThenRunsDownTheSlopeOnRelease) {
  SlopeAvalanche scene(smallSlope(30.0f, kRelease));
  const float d = scene.config().particleDiameter;
  const AvalancheRun r = run(scene, kSettled, 0.4, 2.0);
  ASSERT_TRUE(scene.released());
  EXPECT_LT(r.releasedAt, kRelease + 0.1) << "the block did not settle behind the wall";

  const double held = kit::meanDisplacement(r.settled, r.beforeRelease, scene.downSlope());
  const double ran = kit::meanDisplacement(r.beforeRelease, r.end, scene.downSlope());
  std::printf("30 deg: held %.3f d, after release %.2f d\n", held / d, ran / d);
  EXPECT_LT(std::abs(held), 0.5 * d);
  // Sliding on mu = 0.3 at 30 degrees: a = g (sin - mu cos) = 2.4 m/s², 9 d in 0.4 s.
  EXPECT_GT(ran, 5.0 * d);
  const std::vector<SceneMetric> metrics = scene.metrics(r.end);
  EXPECT_GT(metricNamed(metrics, "moved_fraction"), 0.9);
  EXPECT_GT(metricNamed(metrics, "front_x_d"), 5.0);  // well past the wall's place
  EXPECT_EQ(metricNamed(metrics, "released"), 1.0);
}

TEST(SlopeAvalanche, OnAFlatFloorTheReleasedBlockBarelyMoves) {
  SlopeAvalanche scene(smallSlope(0.0f, kRelease));
  const float d = scene.config().particleDiameter;
  const AvalancheRun r = run(scene, kSettled, 0.4, 2.0);
  ASSERT_TRUE(scene.released());
  const double ran = kit::meanDisplacement(r.beforeRelease, r.end, scene.downSlope());
  std::printf("0 deg: after release %.2f d\n", ran / d);
  // Only the open face of the block slumps (a low granular column collapses little).
  EXPECT_LT(std::abs(ran), 2.0 * d);
}

TEST(SlopeAvalanche, WithoutReleaseTheSandStaysBehindTheWall) {
  SlopeAvalanche scene(smallSlope(30.0f, 1e6f));
  const float d = scene.config().particleDiameter;
  const AvalancheRun r = run(scene, kSettled, 0.4, kRelease + 0.4);
  EXPECT_FALSE(scene.released());
  const double held = kit::meanDisplacement(r.settled, r.end, scene.downSlope());
  std::printf("30 deg, held: %.3f d\n", held / d);
  EXPECT_LT(std::abs(held), 0.5 * d);
  for (const BodyState& body : r.end) {
    EXPECT_LT(body.position.x, -0.5f * d) << "granule " << body.id.index << " passed the wall";
  }
}

}  // namespace
}  // namespace sandphys::scenes
