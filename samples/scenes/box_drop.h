#pragma once

#include <cstdint>

#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct BoxDropConfig {
  float particleDiameter = 0.02f;
  Count3 block{8, 8, 8};
  float spacing = kDefaultGranuleSpacing;  // d
  float boxHalfWidth = 12.0f;              // d
  float boxHeight = 60.0f;                 // d
  float dropHeight = 10.0f;                // d, of the lowest layer above the floor
  std::uint64_t seed = 1;
};

/// The smallest useful scene: one block of granules dropped into a smooth box container. Cheap
/// enough for tests and a first look in the viewer.
class BoxDrop final : public kit::SceneWith<BoxDropConfig> {
 public:
  using SceneWith::SceneWith;

  std::string_view name() const override { return "box-drop"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Mean and highest granule centre, m.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  SceneBounds bounds() const override;

 private:
  std::span<const kit::Param<Config>> table() const override;
};

}  // namespace sandphys::scenes
