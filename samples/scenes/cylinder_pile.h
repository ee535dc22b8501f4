#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct CylinderPileConfig {
  float particleDiameter = 0.02f;
  std::uint32_t batches = 1;
  Count3 batch{32, 16, 32};
  float spacing = kDefaultGranuleSpacing;
  float cylinderRadius = 50.0f;
  float cylinderHeight = 100.0f;
  float firstDropHeight = 50.0f;
  float dropGap = 15.0f;
  float settleSpeed = 0.05f;        // m/s
  float maxSecondsPerBatch = 5.0f;  // s
  std::uint64_t seed = 1;
};

/// The benchmark of Longmore et al. 2013, section 5 (Fig. 10): batches of granules dropped into a
/// smooth cylinder wall on a rough (particle) floor, the first firstDropHeight above the floor,
/// each next one dropGap above the pile once the one before has settled. A batch has the paper's
/// count (32 × 16 × 32) but not its square, which at our 2.4 d spacing (the paper's is 2 d) would
/// reach past the wall: its X·Z columns are the lattice columns nearest the axis, Y high.
class CylinderPile final : public kit::SceneWith<CylinderPileConfig> {
 public:
  using SceneWith::SceneWith;

  std::string_view name() const override { return "cylinder-pile"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Drops the next batch once the newest has settled (one read-back per batch).
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_settleTimes.size() >= m_config.batches; }
  std::string status() const override;
  /// Within the wall's radius and not below the floor.
  bool contains(const Vec3& centre) const override;
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  SceneBounds bounds() const override;

  std::uint32_t batchGranules() const {
    return m_config.batch[0] * m_config.batch[1] * m_config.batch[2];
  }
  /// Largest distance of a dropped batch's particle from the axis, m.
  float batchReach() const;
  /// pileSurface of the contained granules with the granule's outer radius, which only build()
  /// sets (0 before).
  float pileTop(std::span<const BodyState> bodies) const;

 private:
  std::span<const kit::Param<Config>> table() const override;
  void dropBatch(World& world, float bottomLayerY, double simTime);

  std::uint32_t m_batchesDropped = 0;
  kit::SettleWait m_wait;
  float m_pileTop = 0.0f;  // m, when the newest batch was dropped
  float m_granuleMass = 0.0f;
  float m_granuleOuterRadius = 0.0f;
  std::vector<double> m_settleTimes;  // s, each batch's wait
};

}  // namespace sandphys::scenes
