#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// A block of sand on a tilted floor, held by a retaining wall and released once it has settled,
/// so that it runs down the slope onto a flat run-out floor.
///
/// Geometry (x horizontal and downhill, y up, z across): the slope is a Plane through the origin
/// tilted by slopeAngle about z, so its surface is y = -x·tan(angle). The retaining wall is the
/// vertical plane x = 0 (sand on the x < 0 side); the block sits uphill of it, each lattice
/// column resting on the slope beneath it (a block sheared along the slope, not a box hanging in
/// the air). The slope's foot is at x = slopeLength, where the flat run-out floor (the bottom of
/// the container box) continues to x = slopeLength + runoutLength. The box's other walls close
/// the channel behind the block and on both sides. Every surface has the friction `friction`.
///
/// Releasing moves the wall beyond the end of the run-out (World::setCollider). The metrics
/// measure the motion since then: the read-back at release is the reference.
class SlopeAvalanche final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Tilt of the slope from horizontal, degrees; [0, 60]. 0 is a flat floor.
    float slopeAngle = 30.0f;
    /// Granules along x (down the slope), y (layers) and z (across).
    Count3 block{14, 6, 12};
    /// Coulomb friction coefficient of the slope, the run-out floor and the walls against grains;
    /// the block slides as a whole when tan(slopeAngle) exceeds it.
    float friction = 0.4f;
    /// Earliest simulated time at which the retaining wall is removed, s; the wall goes at the
    /// first frame after it in which the block has settled (or maxSettleSeconds later). A time
    /// beyond the run keeps the wall in place.
    float releaseTime = 0.6f;
    /// Horizontal length of the slope from the retaining wall to its foot, d.
    float slopeLength = 40.0f;
    /// Length of the flat run-out floor beyond the foot, d.
    float runoutLength = 50.0f;
    /// A granule counts as moved when it is this far from where it was at release, d.
    float movedDistance = 3.0f;
    /// The block (before release) and the avalanche (after it) have settled when the world's
    /// kinetic energy per granule is below ½ m v² for this speed v, m/s.
    float settleSpeed = 0.05f;
    /// Longest wait for the block to settle past releaseTime, and for the avalanche to stop, s.
    float maxSettleSeconds = 4.0f;
    /// Seed of the block's jitter and orientations: same seed, same block.
    std::uint64_t seed = 1;
  };

  /// Makes the scene with default parameters.
  SlopeAvalanche() = default;
  /// Makes the scene with `config`.
  explicit SlopeAvalanche(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "slope-avalanche".
  std::string_view name() const override { return "slope-avalanche"; }
  /// Capacity for exactly the block; a speed guard and time step sized for the drop from the top
  /// of the block to the run-out floor.
  WorldSettings worldSettings() const override;
  /// The container, the slope, the retaining wall and the block.
  void build(World& world) override;
  /// Removes the wall once the release time has come and the block has settled (one
  /// World::readBodies then, for the reference); detects when the avalanche has stopped.
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once the wall was removed and the sand has come to rest again.
  bool finished() const override { return m_finished; }
  /// "held", "released at t s", "stopped".
  std::string status() const override;
  /// Inside the container and above the slope.
  bool contains(const Vec3& centre) const override;
  /// Since the release (since build before it): centre of mass displacement down the slope,
  /// front position, fraction of granules that moved more than movedDistance.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The container box.
  SceneBounds bounds() const override;

  /// Granules in the block.
  std::uint32_t blockGranules() const;
  /// Unit vector down the slope (x and y; z is 0).
  Vec3 downSlope() const;
  /// Whether the wall has been removed.
  bool released() const { return m_released; }
  /// Simulated time of the release, s (negative before it).
  double releasedAt() const { return m_releasedAt; }
  /// Distance (m) the granules' centre of mass moved down the slope from `reference` to
  /// `bodies` (granules matched by body index; others ignored).
  double comDisplacement(std::span<const BodyState> reference,
                         std::span<const BodyState> bodies) const;

 private:
  /// The channel in m: x from back to end, z within ±halfWidth, y from floor to top.
  struct Channel {
    float back = 0.0f;
    float end = 0.0f;
    float halfWidth = 0.0f;
    float floor = 0.0f;
    float top = 0.0f;
  };
  Channel channel() const;
  float d() const { return m_config.particleDiameter; }
  float tanAngle() const;
  /// Height above the slope surface (vertical, m) of the lowest centres of each column.
  float columnLift() const;
  /// x of the i-th column of the block, m (i = 0 next to the wall).
  float columnX(std::uint32_t i) const;

  Config m_config;
  ColliderId m_wall;
  std::vector<BodyState> m_reference;
  double m_releasedAt = -1.0;
  double m_minSettleTime = 0.0;
  float m_granuleMass = 0.0f;
  bool m_released = false;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
