#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/analysis/heap.h>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct ReposeScupperConfig {
  float particleDiameter = 0.02f;
  std::uint32_t granules = 1200;
  float friction = 0.5f;
  float wallFriction = 0.5f;
  float outlet = 10.0f;
  float depth = 16.0f;
  float reservoirWidth = 12.0f;
  float ledge = 12.0f;
  float sumpLength = 40.0f;
  float wallMargin = 3.0f;
  float youngsModulus = 0.0f;  // Pa
  float restitution = 0.5f;
  float releaseTime = 0.5f;  // s
  float settleSpeed = 0.02f;
  float maxSettleSeconds = 2.0f;
  float minDrainSeconds = 0.5f;
  float maxDrainSeconds = 8.0f;
  float stepsPerContact = 10.0f;
  std::uint64_t seed = 1;
};

/// The angle of repose as Longmore et al. 2013 measure it (section 6.1.4, Fig. 15): sand settled
/// in a reservoir on a ledge runs out through a scupper, a slot at the foot of its wall, into a
/// sump, until the pile there buries the slot; the pile's flank stands at the angle of repose.
///
/// Geometry (y up; the slot runs along z, the sand flows toward +x): one box holds everything,
/// `depth` across in z. The sump's rough floor (particle centres at y = 0) runs from the ledge's
/// face at x = 0 to sumpLength; the ledge, `ledge` high, carries the reservoir, reservoirWidth
/// wide between the box's end wall and the gate, which stands flush with the ledge's face and
/// rises by `outlet` at the release. A sink past the sump's end takes what runs off. The walls
/// keep wallFriction whatever the grains' μ (as in the paper's Fig. 22); the sump floor's
/// particles have the grains' μ.
class ReposeScupper final : public kit::SceneWith<ReposeScupperConfig> {
 public:
  using SceneWith::SceneWith;

  std::string_view name() const override { return "repose-scupper"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Raises the gate once the reservoir has settled; then waits for the sand to rest.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_course.done(); }
  /// "settling", "draining", "settled" or "stopped" (the wait ran out).
  std::string status() const override;
  /// In the reservoir or over the sump's floor.
  bool contains(const Vec3& centre) const override;
  /// The angle of repose and its fit, the granules in the reservoir, the sump and lost.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  SceneBounds bounds() const override;
  /// From the side (+z, a little above): the reservoir, the slot and the sump's pile in profile.
  SceneView view(const std::optional<SceneBounds>&) const override {
    return {bounds(), 0.25f, 0.3f};
  }

  /// The sump's pile and its angle (flank read wallMargin clear of the side walls); throws
  /// InvalidArgument when the pile is too small to have a flank.
  analysis::HeapAngle heapAngle(std::span<const BodyState> bodies) const;
  /// The alive granules of `bodies`: in the reservoir, in the sump, and in all.
  struct GranuleCounts {
    std::uint32_t reservoir = 0, sump = 0, alive = 0;
  };
  GranuleCounts countGranules(std::span<const BodyState> bodies) const;
  /// Simulated time the gate rose, s (negative before).
  double releasedAt() const { return m_course.actStart(); }
  /// The fill's lattice, bottom layer first, `granules` in all, clear of every wall.
  std::vector<GranuleBlock> fillBlocks() const;

 private:
  std::span<const kit::Param<Config>> table() const override;
  bool inSump(const Vec3& centre) const;       // over the sump's floor
  bool inReservoir(const Vec3& centre) const;  // in the reservoir or the scupper
  /// Height of the walls' top above the sump's floor, m.
  float wallTop() const;
  Box gate(bool open) const;  // open: raised by the outlet
  RoughFloor sumpFloor() const;

  ColliderId m_gate;
  kit::Course m_course;
  double m_endTime = -1.0;  // s, when the sand came to rest
};

}  // namespace sandphys::scenes
