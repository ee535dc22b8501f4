// The compression scene at CI size: a plunger loads a settled pile and lets it go. Sand is not
// elastic: the unloading curve lies below the loading one (hysteresis) and the stress is back at
// zero before the strain is (only part of it is recovered). 144 granules in a cylinder 12 d wide,
// pressed to 3 kPa at 0.1 m/s; about 30 s on two llvmpipe cores.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "scenes/compression.h"
#include "support/scene_metric.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

constexpr float kFrame = 1.0f / 120.0f;
constexpr double kLongestRun = 8.0;

TEST(Compression, UnloadingFollowsAnotherPathAndLeavesAResidualStrain) {
  Compression::Config config;
  config.radius = 6.0f;
  config.layers = 16;
  config.maxStress = 3000.0f;
  config.plungerSpeed = 0.1f;
  config.stepsPerContact = kMinStepsPerContact;
  Compression scene(config);
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  runUntilFinished(scene, world, kFrame, kLongestRun);
  ASSERT_TRUE(scene.finished()) << scene.status();
  const SceneSeries stressStrain = scene.series().at(0);
  const double maxStrain = testing::metricNamed(stressStrain.derived, "max_strain");
  const double residualStrain = testing::metricNamed(stressStrain.derived, "residual_strain");
  const auto& curve = stressStrain.points;
  const std::size_t turn = scene.turnIndex();
  ASSERT_GT(turn, 5u) << "a loading curve of a few frames at least";
  ASSERT_GT(curve.size(), turn + 2);
  std::printf(
      "granules %llu: peak %.0f Pa at strain %.4f; residual strain %.4f, recovered %.2f; "
      "%zu contacts at rest, %zu at the peak\n",
      static_cast<unsigned long long>(scene.granules()), curve[turn - 1][1], maxStrain,
      residualStrain, testing::metricNamed(stressStrain.derived, "recovered_fraction"),
      scene.atRest().contacts.size(), scene.atPeak().contacts.size());
  EXPECT_GE(curve[turn - 1][1], config.maxStress);
  // Loading raises the stress with the strain (allowing for the noise of single frames).
  EXPECT_GT(curve[turn - 1][1], 1.5 * curve[turn / 2][1]);
  // Hysteresis: at half the peak strain, unloading carries less stress than loading did.
  const double halfway = 0.5 * maxStrain;
  auto stressAt = [&](std::size_t from, std::size_t to) {
    double best = 1e300, stress = 0.0;
    for (std::size_t i = from; i < to; ++i) {
      const double gap = std::abs(curve[i][0] - halfway);
      if (gap < best) best = gap, stress = curve[i][1];
    }
    return stress;
  };
  const double loading = stressAt(0, turn);
  const double unloading = stressAt(turn, curve.size());
  std::printf("at strain %.4f: loading %.0f Pa, unloading %.0f Pa\n", halfway, loading, unloading);
  EXPECT_LT(unloading, 0.8 * loading);
  // Only part of the strain comes back.
  EXPECT_GT(residualStrain, 0.05 * maxStrain);
  EXPECT_LT(residualStrain, maxStrain);
  EXPECT_GT(scene.atRest().contacts.size(), 0u);
  EXPECT_GT(scene.atPeak().contacts.size(), scene.atRest().contacts.size() / 2);
}

}  // namespace
}  // namespace sandphys::scenes
