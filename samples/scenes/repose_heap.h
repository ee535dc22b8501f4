#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/analysis/heap.h>

#include "scenes/kit/pour.h"

namespace sandphys::scenes {

struct ReposeHeapConfig {
  float particleDiameter = 0.02f;
  std::uint32_t granules = 3000;
  float friction = 0.5f;
  float outlet = 5.0f;
  float rate = 400.0f;
  float pourHeight = 20.0f;
  float floorRadius = 40.0f;
  float youngsModulus = 0.0f;
  float restitution = 0.5f;
  float settleSpeed = 0.02f;
  float maxSettleSeconds = 3.0f;
  float stepsPerContact = 10.0f;
  std::uint64_t seed = 1;
};

/// The angle of repose of a poured heap (Longmore et al. 2013, section 6.1.4, Fig. 22): a narrow
/// emitter high above a rough floor (a disc of static particles whose centres are at y = 0) pours
/// at a steady rate; once the heap has settled, its angle comes from a robust line through its
/// surface granules (analysis::angleOfRepose). Grains that roll off the floor fall into a sink.
/// Unlike the paper, the heap is poured from above (no reservoir and scupper) and the floor's
/// friction is the grains' μ.
class ReposeHeap final : public kit::PourScene<ReposeHeapConfig> {
 public:
  using PourScene::PourScene;

  std::string_view name() const override { return "repose-heap"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// On or above the floor, within its radius.
  bool contains(const Vec3& centre) const override;
  /// The angle of repose and its fit, the heap's height, the granules on and off the floor.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  SceneBounds bounds() const override;

  /// The heap's surface and angle from the granules in `bodies`; throws InvalidArgument when the
  /// heap is too small to have a flank.
  analysis::HeapAngle heapAngle(std::span<const BodyState> bodies) const;
  /// Floor radius, d, on which a cone of `granules` settled granules with its flank at
  /// `angleDegrees` ends a margin short of the edge.
  static float floorRadiusHolding(std::uint32_t granules, float angleDegrees);

 private:
  std::span<const kit::Param<Config>> table() const override;
};

}  // namespace sandphys::scenes
