#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "scenes/slope_avalanche.h"

namespace sandphys::scenes {

/// The sand of slope-avalanche released onto a structure of two wooden blocks that Bullet
/// simulates: a low wide block lying on the run-out floor a little beyond the slope's foot, and a
/// tall thin plank standing on it, broadside to the slope. The blocks touch the sand through a
/// sandphys::bullet::Bridge (their collision shapes sampled into particles); Bullet handles the
/// blocks against each other and against the run-out floor. The avalanche runs over the low block
/// and topples the plank.
class BlockAvalanche final : public Scene {
 public:
  /// The structure's parameters; lengths in particle diameters d (the slope's).
  struct Config {
    /// Gap between the slope's foot and the low block's uphill face, d.
    float blockDistance = 6.0f;
    /// The low block's size: along the run-out (x), height (y), across (z), d.
    Vec3 lowBlock{6.0f, 4.0f, 10.0f};
    /// The plank's size, same axes, d: thin along x, so that the sand pushes it over.
    Vec3 plank{2.0f, 10.0f, 8.0f};
    /// Density of both blocks, kg/m³ (wood).
    float density = 500.0f;
    /// Friction between the blocks and between a block and the floor (Bullet's contacts).
    float blockFriction = 0.6f;
  };

  BlockAvalanche();
  ~BlockAvalanche() override;
  BlockAvalanche(const BlockAvalanche&) = delete;
  BlockAvalanche& operator=(const BlockAvalanche&) = delete;

  Config& config() { return m_config; }
  /// The sand part: block, slope, wall and release (change it before build()).
  SlopeAvalanche& slope() { return m_slope; }
  const SlopeAvalanche& slope() const { return m_slope; }

  // The Scene interface (contracts in Scene).

  /// "avalanche".
  std::string_view name() const override { return "avalanche"; }
  /// The slope's settings, with room for the blocks' particles.
  WorldSettings worldSettings() const override;
  /// The slope's sand and container; a new Bullet world with its floor and the two blocks,
  /// coupled to `world`.
  void build(World& world) override;
  /// Both worlds through the bridge.
  StepReport step(World& world, float frameDt) override;
  /// The slope's release logic.
  void update(World& world, const StepReport& report, double simTime) override;
  /// The sand has stopped after the release.
  bool finished() const override { return m_slope.finished(); }
  /// The slope's status and the plank's tilt.
  std::string status() const override;
  bool contains(const Vec3& centre) const override { return m_slope.contains(centre); }
  /// The slope's metrics, and each block's tilt (deg) and displacement (m) since build.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// The slope's parameters and the structure's, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The slope's channel.
  SceneBounds bounds() const override { return m_slope.bounds(); }
  /// "low-block" and "plank", as Bullet has them now.
  std::vector<SceneBody> bodies(const World& world) const override;
  /// What the bridge pushed from Bullet in the last step.
  std::vector<RecordedInput> externalInputs() const override;

 private:
  struct Blocks;
  // The blocks as Bullet has them now (the sand world is not needed).
  std::vector<SceneBody> blockBodies() const;
  float d() const { return m_slope.config().particleDiameter; }

  Config m_config;
  SlopeAvalanche m_slope;
  std::unique_ptr<Blocks> m_blocks;
};

}  // namespace sandphys::scenes
