#pragma once

#include <memory>
#include <span>
#include <vector>

#include "scenes/slope_avalanche.h"

namespace sandphys::scenes {

/// Lengths in the slope's particle diameters d; the parameter table in the .cpp describes the
/// fields that are parameters.
struct BlockAvalancheConfig {
  float blockDistance = 6.0f;
  Vec3 lowBlock{6.0f, 4.0f, 10.0f};  // d, along the run-out (x), height (y), across (z)
  Vec3 plank{2.0f, 10.0f, 8.0f};     // d, same axes: thin along x, so that the sand pushes it over
  float density = 500.0f;            // kg/m³
  float blockFriction = 0.6f;
};

/// The sand of slope-avalanche released onto two wooden blocks that Bullet simulates: a low wide
/// block on the run-out floor blockDistance beyond the slope's foot, and a tall thin plank
/// standing on it broadside to the slope. The blocks meet the sand through a
/// sandphys::bullet::Bridge (their shapes sampled into particles), and each other and the floor
/// in Bullet. The avalanche runs over the low block and topples the plank.
class BlockAvalanche final : public SlopeAvalanche {
 public:
  BlockAvalanche();
  ~BlockAvalanche() override;

  std::string_view name() const override { return "avalanche"; }
  WorldSettings worldSettings() const override;
  /// The slope's sand and container, and a new Bullet world with its floor and the two blocks.
  void build(World& world) override;
  StepReport step(World& world, float frameDt) override;
  /// The slope's status and the plank's tilt.
  std::string status() const override;
  /// The slope's metrics, and each block's tilt (deg) and displacement (m) since build.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// The slope's parameters, then the blocks'.
  std::vector<SceneParameter> parameters() override;
  /// "low-block" and "plank", as Bullet has them now.
  std::vector<SceneBody> bodies(const World& /*world*/) const override { return blockBodies(); }
  std::vector<RecordedInput> externalInputs() const override;

 private:
  struct Blocks;
  std::vector<SceneBody> blockBodies() const;

  BlockAvalancheConfig m_blocksConfig;
  std::unique_ptr<Blocks> m_blocks;
};

}  // namespace sandphys::scenes
