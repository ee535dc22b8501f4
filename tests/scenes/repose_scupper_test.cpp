// The repose-scupper scene at CI size on a real (headless) World: sand run out of a reservoir
// through a slot piles up in the sump until it buries the slot, and that pile stands clearly
// steeper with more friction (the paper's Figs. 15 and 22).
//
// What the small version trades for time (a fill takes 10-15 s on two llvmpipe cores, and the test
// runs six): 600 granules in a container 12 d deep, a reservoir 12 d wide on a ledge 8 d high, a
// slot 10 d high (a lower one jams at mu = 0.5: at 4 d only 34 granules passed), the fewest
// substeps per contact a World accepts. The pile in the sump is about 10 d high and has tens of
// surface cells on its flank.
#include <gtest/gtest.h>

#include <cstdio>

#include "scenes/repose_scupper.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

constexpr float kFrame = 1.0f / 60.0f;
constexpr std::uint32_t kGranules = 600;
constexpr float kLedge = 8.0f;
// Release (under a second) plus the drain, which ends when the sand is calm: about 5 s at
// mu = 0.5, where avalanches keep feeding the flank.
constexpr double kLongestRun = 10.0;

struct Sump {
  analysis::HeapAngle angle;
  bool settled = false;
  ReposeScupper::GranuleCounts granules;
};

Sump drain(float friction, std::uint64_t seed) {
  ReposeScupper::Config config;
  config.granules = kGranules;
  config.friction = friction;
  config.outlet = 10.0f;
  config.depth = 12.0f;
  config.reservoirWidth = 12.0f;
  config.ledge = kLedge;
  config.sumpLength = 32.0f;
  config.stepsPerContact = kMinStepsPerContact;
  config.seed = seed;
  ReposeScupper scene(config);
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  runUntilFinished(scene, world, kFrame, kLongestRun);
  Sump sump;
  sump.settled = scene.finished() && scene.status() == "settled";
  const std::vector<BodyState> bodies = world.readBodies();
  sump.granules = scene.countGranules(bodies);
  sump.angle = scene.heapAngle(bodies);
  std::printf(
      "mu %.1f, seed %u: %s at %.2f s (released at %.2f s), %u granules in the reservoir, %u in "
      "the sump, "
      "%u alive; angle %.2f deg (R2 %.3f over %zu surface cells), height %.2f d\n",
      friction, unsigned(seed), scene.status().c_str(), world.simulatedTime(), scene.releasedAt(),
      sump.granules.reservoir, sump.granules.sump, sump.granules.alive, sump.angle.degrees,
      sump.angle.fit.line.rSquared, sump.angle.radius.size(),
      sump.angle.peakHeight / config.particleDiameter);
  return sump;
}

// Every slot of the fill's lattice, widened by a granule's reach and its largest jitter, lies in
// the reservoir: x between the far wall and the gate (2 d thick, its face at x = -2 d), z between
// the side walls, y above the ledge. A granule started inside a wall is thrown out at once.
void expectFillClearOfTheWalls(const ReposeScupper::Config& config) {
  const ReposeScupper scene(config);
  const float d = config.particleDiameter;
  const float gate = -2.0f * d;
  const float far = gate - config.reservoirWidth * d;
  const float side = 0.5f * config.depth * d;
  std::uint32_t granules = 0;
  for (const GranuleBlock& block : scene.fillBlocks()) {
    const float reach = static_cast<float>(kGranuleReach) * d + block.jitter * block.spacing;
    const Vec3 half{0.5f * static_cast<float>(block.countX - 1) * block.spacing,
                    0.5f * static_cast<float>(block.countY - 1) * block.spacing,
                    0.5f * static_cast<float>(block.countZ - 1) * block.spacing};
    EXPECT_GT(block.center.x - half.x - reach, far);
    EXPECT_LT(block.center.x + half.x + reach, gate);
    EXPECT_GT(block.center.z - half.z - reach, -side);
    EXPECT_LT(block.center.z + half.z + reach, side);
    EXPECT_GT(block.center.y - half.y - reach, config.ledge * d);
    granules += block.countX * block.countY * block.countZ;
  }
  EXPECT_EQ(granules, config.granules);
}

TEST(ReposeScupper, TheFillStartsClearOfTheWalls) {
  ReposeScupper::Config config;
  expectFillClearOfTheWalls(config);
  for (float depth : {6.0f, 12.0f, 16.0f, 17.0f, 23.5f}) {
    for (float width : {6.0f, 12.0f, 13.3f, 20.0f}) {
      config.depth = depth;
      config.reservoirWidth = width;
      config.granules = 257;
      SCOPED_TRACE(::testing::Message() << "depth " << depth << " d, reservoir " << width << " d");
      expectFillClearOfTheWalls(config);
    }
  }
}

// One fill is one realisation: the angle at mu = 0.5 ranged from 29 to 41 degrees over six (three
// seeds, with and without sorts of the granules), the gap to mu = 0.1 from 7 to 17. So the gap is
// taken as the mean over three seeds, whose spread is about 2 degrees.
TEST(ReposeScupper, TheSumpPileBuriesTheSlotAndStandsSteeperWithMoreFriction) {
  double gap = 0.0;
  constexpr std::uint64_t kSeeds = 3;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const Sump rough = drain(0.5f, seed);
    const Sump smooth = drain(0.1f, seed);
    for (const Sump* sump : {&rough, &smooth}) {
      EXPECT_TRUE(sump->settled);
      // Every granule left is in the reservoir or the sump: none went through a wall or stuck in
      // the slot. A few roll off the sump's end into the sink, not many.
      EXPECT_EQ(sump->granules.reservoir + sump->granules.sump, sump->granules.alive);
      EXPECT_GT(sump->granules.alive, kGranules - kGranules / 20);
      EXPECT_GT(sump->granules.sump, 150u) << "a pile formed in the sump";
      // The flow stops because the pile buries the slot, whose foot is the ledge's top: the pile
      // reaches that high (its top centres lie half a granule below the surface).
      EXPECT_GT(sump->angle.peakHeight, (kLedge - 1.0f) * 0.02f);
      EXPECT_GE(sump->angle.radius.size(), 10u) << "a flank of at least ten surface cells";
      // A straight flank: on a pile about 10 d high, surface cells scattered by a granule's size
      // (about 1 d) about the line give R² of 0.75 to 0.95; a pile that is no slope gives ~0.
      EXPECT_GT(sump->angle.fit.line.rSquared, 0.6) << "the flank is straight";
    }
    EXPECT_GT(smooth.angle.degrees, 5.0) << "a pile, not a spread";
    gap += (rough.angle.degrees - smooth.angle.degrees) / double(kSeeds);
  }
  // The paper's Fig. 22 has about 10 degrees between mu = 0.1 and 0.5, the six fills above 12.4 on
  // average (standard deviation 3.8, so 2.2 for a mean of three): 5 is half the paper's gap and
  // over three such spreads below what was measured, and a friction that changed nothing fails.
  EXPECT_GT(gap, 5.0) << "mean gap between mu = 0.5 and 0.1, degrees";
}

}  // namespace
}  // namespace sandphys::scenes
