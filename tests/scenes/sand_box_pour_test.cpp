// The sand-box-pour scene on a real (headless) World: the emitter keeps its rate and its budget,
// no granule leaves the box, the pile grows as sand is poured, and the scene finishes once the
// pile is at rest. A small pour (240 granules into a 14 d box) keeps each test to seconds on
// llvmpipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/kit/pour.h"
#include "scenes/sand_box_pour.h"
#include "support/scene_metric.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

using testing::metricNamed;

constexpr float kFrame = 1.0f / 60.0f;

SandBoxPour::Config smallPour() {
  return {.rate = 600.0f,
          .granules = 240,
          .boxWidth = 14.0f,
          .boxHeight = 20.0f,
          .pourHeight = 14.0f,
          .outlet = 10.0f};
}

// Pours `granules` with the small settings until the scene reports the pile settled, checking
// the emitter's count against rate x time after every frame and that every granule ends inside
// the box. Returns the pile height, m.
float pourUntilSettled(std::uint32_t granules) {
  SCOPED_TRACE(std::to_string(granules) + " granules");
  SandBoxPour::Config config = smallPour();
  config.granules = granules;
  SandBoxPour pour(config);
  const WorldSettings settings = pour.settings();
  // The budget is the whole capacity: the emitter can never add more.
  EXPECT_EQ(settings.maxBodies, granules);
  World world(testing::gpu(), settings);
  pour.build(world);
  EXPECT_EQ(pour.status(), "pouring 0/" + std::to_string(granules)) << "the pour starts at once";

  const float d = pour.config().particleDiameter;
  const double rate = pour.config().rate;
  const double budget = granules;
  const double layer = kit::emitterLayerGranules(0.5f * pour.config().outlet * d, d);
  EXPECT_EQ(layer, 25.0);  // 5 x 5 slots across 10 d at 2.4 d
  while (!pour.finished() && world.simulatedTime() < 2.0) {
    const StepReport report = world.step(kFrame);
    pour.update(world, report, world.simulatedTime());
    const double t = world.simulatedTime();
    const std::uint32_t spawned = world.granulesSpawned();
    // Granules come in layers of the emitter's lattice, so the count may lag the ideal rate by
    // up to one layer; it never runs ahead of it or past the budget.
    EXPECT_LE(spawned, budget) << "t = " << t;
    EXPECT_LE(spawned, rate * t + 1.0) << "t = " << t << " s";
    EXPECT_GE(spawned, std::min(budget, rate * t) - layer) << "t = " << t << " s";
    EXPECT_EQ(report.stats.granulesAlive, spawned);
  }
  EXPECT_TRUE(pour.finished()) << "not settled after " << world.simulatedTime() << " s";
  EXPECT_EQ(world.granulesSpawned(), granules);

  const std::vector<BodyState> bodies = world.readBodies();
  const std::vector<SceneMetric> metrics = pour.metrics(bodies);
  EXPECT_EQ(metricNamed(metrics, "granules_poured"), granules);
  for (const BodyState& body : bodies) {
    EXPECT_TRUE(pour.contains(body.position))
        << "granule " << body.id.index << " escaped to (" << body.position.x << ", "
        << body.position.y << ", " << body.position.z << ")";
  }
  // The pile's top and footprint as the scene measures them (its granules at rest), m.
  const auto height = static_cast<float>(metricNamed(metrics, "pile_height_m"));
  const auto footprint = static_cast<float>(metricNamed(metrics, "footprint_radius_m"));
  std::printf("%u granules: pile height %.2f d, footprint radius %.2f d, settled at %.3f s\n",
              granules, height / d, footprint / d, world.simulatedTime());
  // Inside the box, below the emitter: the grains have landed.
  EXPECT_LE(footprint, 7.0f * std::sqrt(2.0f) * d + 1.2f * d);
  EXPECT_LT(height, 14.0f * d);
  return height;
}

TEST(SandBoxPour, PoursAtItsRateWithinItsBudgetAndThePileGrows) {
  const float d = smallPour().particleDiameter;
  const float small = pourUntilSettled(80);
  const float large = pourUntilSettled(240);
  // Three times the sand on the same 14 x 14 d floor: the pile is clearly higher.
  EXPECT_GT(small, 2.0f * d);
  EXPECT_GT(large, small + 1.5f * d);
}

TEST(SandBoxPour, PourWaitsForTheBedToSettle) {
  SandBoxPour::Config config = smallPour();
  config.granules = 40;
  config.block = {4, 2, 4};
  SandBoxPour pour(config);
  EXPECT_EQ(pour.settings().maxBodies, 40u + 32u);
  World world(testing::gpu(), pour.settings());
  pour.build(world);
  EXPECT_EQ(world.granulesSpawned(), 32u);
  EXPECT_EQ(pour.status(), "settling");

  // Two layers fall about 1.4 d onto the floor: nothing is poured until they have landed. The
  // pour starts on the frame the status leaves "settling", at that frame's simulated time.
  double pourStart = -1.0;
  while (pourStart < 0.0 && world.simulatedTime() < 1.0) {
    const StepReport report = world.step(kFrame);
    pour.update(world, report, world.simulatedTime());
    if (pour.status() == "settling") {
      ASSERT_EQ(world.granulesSpawned(), 32u);
    } else {
      pourStart = world.simulatedTime();
    }
  }
  EXPECT_GT(pourStart, 0.1);
  EXPECT_LT(pourStart, 1.0);
  while (world.simulatedTime() < pourStart + 0.2) {
    const StepReport report = world.step(kFrame);
    pour.update(world, report, world.simulatedTime());
  }
  EXPECT_EQ(world.granulesSpawned(), 72u);
  EXPECT_EQ(metricNamed(pour.metrics(world.readBodies()), "granules_poured"), 40.0);
}

TEST(SandBoxPour, RefusesARateItsEmitterCannotPourGently) {
  SandBoxPour pour(smallPour());
  pour.config().rate = 5000.0f;  // 25 slots would have to move at 10.6 m/s
  try {
    (void)pour.settings();
    FAIL() << "accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("rate 5000"), std::string::npos) << error.what();
  }
  pour.config().rate = 600.0f;
  pour.config().outlet = 14.0f;  // as wide as the box: grains would start in the walls
  EXPECT_THROW((void)pour.settings(), InvalidArgument);
}

}  // namespace
}  // namespace sandphys::scenes
