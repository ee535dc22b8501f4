#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/pour.h"

namespace sandphys::scenes {

struct SandBoxPourConfig {
  float particleDiameter = 0.02f;
  float rate = 1000.0f;  // granules/s
  std::uint32_t granules = 1500;
  float boxWidth = 40.0f;
  float boxHeight = 30.0f;
  float pourHeight = 20.0f;   // "emitter-height"
  float outlet = 13.0f;       // "emitter-size"
  Count3 block{0, 0, 0};      // the bed; none when a count is 0
  float settleSpeed = 0.05f;  // m/s
  float maxSettleSeconds = 3.0f;
  float youngsModulus = 0.0f;  // Pa
  std::uint64_t seed = 1;
};

/// Sand poured into a smooth box from a square emitter high above its floor (kit::Pour), at a fixed
/// rate until its budget is spent: the grains heap up into a pile. Optionally the pour lands on a
/// bed (a block resting on the floor) and starts once the bed has settled.
class SandBoxPour final : public kit::PourScene<SandBoxPourConfig> {
 public:
  using PourScene::PourScene;

  std::string_view name() const override { return "sand-box-pour"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  void update(World& world, const StepReport& report, double simTime) override;
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  SceneBounds bounds() const override;

 private:
  std::span<const kit::Param<Config>> table() const override;
  float halfWidth() const { return 0.5f * m_config.boxWidth * d(); }
  std::uint32_t bedGranules() const {
    return m_config.block[0] * m_config.block[1] * m_config.block[2];
  }
  /// Top and footprint radius of the pile, m: the 99th percentiles of the heights and of the
  /// distances from the pour axis of the contained granules slower than 0.3 m/s (not the ones
  /// still falling), each plus the granule's reach; 0 without such granules.
  std::array<float, 2> pileExtent(std::span<const BodyState> bodies) const;
};

}  // namespace sandphys::scenes
