#pragma once

#include <cstdint>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// The smallest useful scene: one block of granules dropped into a smooth box container. Cheap
/// enough for tests and a first look in the viewer.
class BoxDrop final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Granules along x, y (layers) and z.
    Count3 block{8, 8, 8};
    /// Lattice spacing of the block, d.
    float spacing = kDefaultGranuleSpacing;
    /// Half width of the box along x and z, d.
    float boxHalfWidth = 12.0f;
    /// Height of the box, d.
    float boxHeight = 60.0f;
    /// Height of the block's lowest layer above the box floor, d.
    float dropHeight = 10.0f;
    /// Seed of the block's jitter and orientations.
    std::uint64_t seed = 1;
  };

  /// Makes the scene with default parameters.
  BoxDrop() = default;
  /// Makes the scene with `config`.
  explicit BoxDrop(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "box-drop".
  std::string_view name() const override { return "box-drop"; }
  /// Capacity for exactly the block.
  WorldSettings worldSettings() const override;
  /// The box container and the block.
  void build(World& world) override;
  /// Inside the box.
  bool contains(const Vec3& centre) const override;
  /// Mean and highest granule centre, m.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// block, seed and diameter.
  std::vector<SceneParameter> parameters() override;
  /// The box.
  SceneBounds bounds() const override;

 private:
  float d() const { return m_config.particleDiameter; }

  Config m_config;
};

}  // namespace sandphys::scenes
