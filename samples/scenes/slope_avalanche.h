#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct SlopeAvalancheConfig {
  float particleDiameter = 0.02f;
  float slopeAngle = 30.0f;  // degrees
  Count3 block{14, 6, 12};
  float friction = 0.4f;
  float releaseTime = 0.6f;  // s
  float slopeLength = 40.0f;
  float runoutLength = 50.0f;
  float movedDistance = 3.0f;
  float settleSpeed = 0.05f;
  float maxSettleSeconds = 4.0f;
  std::uint64_t seed = 1;
};

/// A block of sand on a slope, held by a retaining wall that is removed once the block has
/// settled, so that it runs down onto a flat run-out floor.
///
/// Geometry (x downhill, y up, z across): the slope is the plane y = -x·tan(angle) through the
/// origin; the wall is the plane x = 0 with the sand on the x < 0 side, each lattice column
/// resting on the slope beneath it. The run-out (the bottom of the container box) runs from the
/// slope's foot at x = slopeLength to slopeLength + runoutLength. Every surface has `friction`.
/// The metrics measure the motion since the release.
class SlopeAvalanche : public kit::SceneWith<SlopeAvalancheConfig> {
 public:
  using SceneWith::SceneWith;

  std::string_view name() const override { return "slope-avalanche"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Removes the wall once the block has settled after releaseTime (one read-back then, for the
  /// reference of the metrics).
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_course.done(); }
  /// "held", "released at t s", "came to rest".
  std::string status() const override;
  /// Inside the container and above the slope.
  bool contains(const Vec3& centre) const override;
  /// Since the release: centre of mass displacement down the slope, the front's position and the
  /// fraction of granules that moved more than movedDistance.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// The channel: x from behind the block to the run-out's end, y from the run-out up.
  SceneBounds bounds() const override;
  /// The slope and its run-out from the side (+z, a little above), up to a little over the sand:
  /// where the sand goes, not the walls' empty tops.
  SceneView view(const std::optional<SceneBounds>& contents) const override;

  /// Unit vector down the slope.
  Vec3 downSlope() const;
  bool released() const { return m_course.actStart() >= 0.0; }
  /// Simulated time of the release, s (negative before it).
  double releasedAt() const { return m_course.actStart(); }

 private:
  std::span<const kit::Param<Config>> table() const override;
  /// The slope's tilt, rad.
  float angle() const;
  Vec3 slopeNormal() const;
  /// Height above the slope (vertical, m) of the lowest centres of each column.
  float columnLift() const;
  /// x of the i-th column of the block, m (i = 0 next to the wall).
  float columnX(std::uint32_t i) const;

  ColliderId m_wall;
  kit::Reference m_reference;
  kit::Course m_course;
};

}  // namespace sandphys::scenes
