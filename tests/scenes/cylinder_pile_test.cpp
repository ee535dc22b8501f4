// The cylinder pile on a real (headless) World: what build() places and when update() drops the
// next batch. update() is driven with chosen times and reports, so no simulation is needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string_view>
#include <vector>

#include "scenes/cylinder_pile.h"
#include "support/scene_metric.h"

namespace sandphys::scenes {
namespace {

constexpr float kD = 0.02f;
constexpr float kSpacing = kDefaultGranuleSpacing * kD;
// GranuleBlock jitters each granule by up to `jitter` spacings per axis.
const float kJitter = GranuleBlock{}.jitter * kSpacing + 1e-5f;

class CylinderPileOnGpu : public ::testing::Test {
 protected:
  CylinderPileOnGpu() : m_gpu(GpuContext::headless()) {
    m_pile.config().batch = {4, 2, 4};
    m_pile.config().batches = 2;
    m_world = std::make_unique<World>(m_gpu, m_pile.settings());
    m_pile.build(*m_world);
  }

  std::vector<BodyState> granules() const {
    std::vector<BodyState> result;
    for (const BodyState& body : m_world->readBodies()) {
      if (body.granule) result.push_back(body);
    }
    return result;
  }

  // The scene's metric `name` (those that count batches need no bodies).
  double metric(std::string_view name) const {
    return testing::metricNamed(m_pile.metrics({}), name);
  }

  static StepReport reportWithEnergy(double kineticEnergy) {
    StepReport report;
    report.hasStats = true;
    report.stats.kineticEnergy = kineticEnergy;
    return report;
  }

  GpuContext m_gpu;
  CylinderPile m_pile;
  std::unique_ptr<World> m_world;
};

TEST_F(CylinderPileOnGpu, BuildAddsTheFloorAndTheFirstBatch50DiametersUp) {
  EXPECT_EQ(m_world->bodyCount(), 1u + 32u);
  // The capacity formula (roughFloorParticles) has to match what the world really placed.
  EXPECT_EQ(m_world->particleCount(),
            4u * 32u + roughFloorParticles(RoughFloor{.radius = 1.0f}, kD));
  EXPECT_EQ(metric("batches_dropped"), 1.0);

  const std::vector<BodyState> batch = granules();
  ASSERT_EQ(batch.size(), 32u);
  float lowest = 1e9f;
  float highest = -1e9f;
  float meanX = 0.0f;
  float meanZ = 0.0f;
  for (const BodyState& body : batch) {
    EXPECT_LE(std::hypot(body.position.x, body.position.z), m_pile.batchReach());
    meanX += body.position.x / static_cast<float>(batch.size());
    meanZ += body.position.z / static_cast<float>(batch.size());
    lowest = std::min(lowest, body.position.y);
    highest = std::max(highest, body.position.y);
  }
  // 16 columns nearest the axis: a disc (with ties broken to one side), centred within a column.
  EXPECT_LT(std::hypot(meanX, meanZ), kSpacing);
  EXPECT_NEAR(lowest, 50.0f * kD, kJitter);
  EXPECT_NEAR(highest, 50.0f * kD + kSpacing, kJitter);  // two layers
}

TEST_F(CylinderPileOnGpu, NothingDropsWhileTheBatchIsStillFalling) {
  // A batch released at rest has no kinetic energy yet; it must not count as settled.
  m_pile.update(*m_world, reportWithEnergy(0.0), 0.1);
  EXPECT_EQ(metric("batches_dropped"), 1.0);
  EXPECT_EQ(m_world->bodyCount(), 33u);
}

TEST_F(CylinderPileOnGpu, MovingGrainsHoldTheNextBatchUntilTheTimeLimit) {
  m_pile.update(*m_world, reportWithEnergy(1.0), 2.0);  // 1 J: clearly still moving
  EXPECT_EQ(metric("batches_dropped"), 1.0);
  m_pile.update(*m_world, reportWithEnergy(1.0), m_pile.config().maxSecondsPerBatch + 0.01);
  EXPECT_EQ(metric("batches_dropped"), 2.0);
}

TEST_F(CylinderPileOnGpu, SettledBatchIsFollowedByOne15DiametersAboveThePile) {
  m_pile.update(*m_world, reportWithEnergy(0.0), 2.0);
  EXPECT_EQ(metric("batches_dropped"), 2.0);
  EXPECT_EQ(m_world->bodyCount(), 1u + 64u);
  ASSERT_EQ(metric("batches_settled"), 1.0);
  EXPECT_DOUBLE_EQ(metric("mean_settle_seconds"), 2.0);

  // The first batch never moved: the pile top it was measured from is its top layer plus the
  // granule's outer radius (1.11 d).
  std::vector<BodyState> all = granules();
  ASSERT_EQ(all.size(), 64u);
  const float top = m_pile.pileTop(std::span(all).first(32));
  EXPECT_NEAR(top, 50.0f * kD + kSpacing + 1.1124f * kD, kJitter);
  float lowestNew = 1e9f;
  for (std::size_t i = 32; i < all.size(); ++i) lowestNew = std::min(lowestNew, all[i].position.y);
  EXPECT_NEAR(lowestNew, top + 15.0f * kD, kJitter);

  // The last batch settles: the scene is finished and adds nothing more.
  EXPECT_FALSE(m_pile.finished());
  m_pile.update(*m_world, reportWithEnergy(0.0), 4.0);
  EXPECT_TRUE(m_pile.finished());
  m_pile.update(*m_world, reportWithEnergy(0.0), 20.0);
  EXPECT_EQ(m_world->bodyCount(), 65u);
}

TEST_F(CylinderPileOnGpu, RebuildStartsOver) {
  m_pile.update(*m_world, reportWithEnergy(0.0), 2.0);
  ASSERT_EQ(metric("batches_dropped"), 2.0);
  World fresh(m_gpu, m_pile.settings());
  m_pile.build(fresh);
  EXPECT_EQ(metric("batches_dropped"), 1.0);
  EXPECT_EQ(metric("batches_settled"), 0.0);
  EXPECT_EQ(fresh.bodyCount(), 33u);
}

}  // namespace
}  // namespace sandphys::scenes
