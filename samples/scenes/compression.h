#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// Uniaxial compression of a settled pile (Longmore et al. 2013, sections 6.1.1 and 6.1.3,
/// Figs. 17c and 21), after the paper's protocol: a pile settles in a smooth cylinder on a rough
/// floor; a flat plunger comes down (fast until it touches the sand, then at plungerSpeed) and
/// presses the top flat with a small stress (preloadFraction of maxStress), then eases back up
/// to the lowest height at which the sand no longer pushes on it. From there the experiment
/// runs: the plunger comes down at plungerSpeed until the mean axial stress under it reaches
/// maxStress, then goes back up at the same speed until the stress is zero again. The stress
/// (the plunger's force over the cylinder's cross-section) against the strain (the plunger's
/// travel from the eased height, over the pile's height there) traces the loading and unloading
/// curves; unloading returns along another path (hysteresis) and ends at a residual strain: the
/// sand recovers only part of its compression.
///
/// Geometry (y up): a rough floor (static particles, centres at y = 0) of the cylinder's radius,
/// a Cylinder collider around it, the granules laid on a square lattice inside the cylinder and
/// dropped; the plunger is a kinematic disc of particles (a triangular lattice 0.8 d apart, as
/// sampleMesh covers a surface), 0.75 d narrower than the cylinder (a gap no granule fits
/// through). Its force comes from
/// World::takeBodyForces every frame (32 bytes).
///
/// For the force distributions the scene reads every contact twice, a sync point each: when the
/// pile has settled (atRest()) and at the peak of the load (atPeak()).
class Compression final : public Scene {
 public:
  struct Config {
    float particleDiameter = 0.02f;
    /// Radius of the cylinder and the rough floor, d.
    float radius = 12.0f;
    /// Layers of the lattice the pile is dropped from; granules = layers × the lattice's
    /// granules per layer inside the cylinder (metrics: granules).
    std::uint32_t layers = 12;
    /// Speed of the plunger, m/s, down and up.
    float plungerSpeed = 0.05f;
    /// Largest mean axial stress, Pa: the plunger turns back once it is reached.
    float maxStress = 20000.0f;
    /// The stress that flattens the top before the experiment, as a fraction of maxStress. The
    /// paper uses "a small force" on a pile built from 64 K granules in batches; a pile of a
    /// thousand granules dropped from a loose lattice is far looser, and at a preload of 0.1 the
    /// loading curve is mostly its collapse (13% strain at 3 kPa in a 144-granule pile, against
    /// 6.5% after a preload of 0.5, measured). Half the peak packs it first.
    float preloadFraction = 0.5f;
    /// Coulomb friction coefficient μ of every contact (grains, floor, wall).
    float friction = 0.5f;
    /// Young's modulus of the grains, Pa.
    float youngsModulus = 0.0f;
    /// The pile has settled when its kinetic energy per granule is below ½ m v² for this v, m/s.
    float settleSpeed = 0.02f;
    /// Longest wait for the pile to settle, s.
    float maxSettleSeconds = 3.0f;
    /// Substeps per Hertz contact time at the speed guard (WorldSettings::stepsPerContact).
    float stepsPerContact = 10.0f;
    std::uint64_t seed = 1;
  };

  enum class Phase { Settling, Approach, Preload, Easing, Loading, Unloading, Done };

  /// Every contact at one moment, and the bodies then (for granule-level forces).
  struct Snapshot {
    double time = -1.0;  ///< s; negative until taken
    std::vector<ContactRecord> contacts;
    std::vector<BodyState> bodies;
  };

  Compression() = default;
  explicit Compression(const Config& config) : m_config(config) {}

  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "compression".
  std::string_view name() const override { return "compression"; }
  WorldSettings worldSettings() const override;
  /// The floor, the cylinder, the lattice of granules and the plunger (parked above them).
  void build(World& world) override;
  /// Steers the plunger through its phases and records stress and strain.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_phase == Phase::Done; }
  /// "settling", "approach", "preload", "easing", "loading: σ kPa", "unloading: σ kPa", "done".
  std::string status() const override;
  /// Inside the cylinder, above the floor.
  bool contains(const Vec3& centre) const override;
  /// Granules, the pile's height where the experiment starts, the peak stress and strain, the
  /// residual strain and the fraction of the strain recovered.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "stress_strain": [strain, stress Pa] of the experiment (loading, then unloading),
  /// with max_strain, residual_strain and recovered_fraction.
  std::vector<SceneSeries> series() const override;
  std::vector<SceneParameter> parameters() override;
  SceneBounds bounds() const override;

  Phase phase() const { return m_phase; }
  /// [strain, stress Pa] per frame of the experiment (loading, then unloading).
  const std::vector<std::array<double, 2>>& stressStrain() const { return m_curve; }
  /// Index in stressStrain() of the turn from loading to unloading (the curve's size before).
  std::size_t turnIndex() const { return m_turn; }
  /// Strain at the turn, and where unloading brought the stress back to zero (the residual
  /// strain; the last strain recorded if it never did).
  double maxStrain() const { return m_maxStrain; }
  double residualStrain() const { return m_residualStrain; }
  /// (maxStrain − residualStrain) / maxStrain; 0 before the turn.
  double recoveredFraction() const;
  const Snapshot& atRest() const { return m_atRest; }
  const Snapshot& atPeak() const { return m_atPeak; }
  /// Granules per lattice layer inside the cylinder.
  std::uint32_t granulesPerLayer() const;
  /// Cross-section of the cylinder, m².
  double area() const;

 private:
  float d() const { return m_config.particleDiameter; }
  float plungerRadius() const;
  /// Granules along each side of the square lattice layer inside the cylinder.
  std::uint32_t latticeSide() const;
  /// The plunger's body: its face, a disc of particles in the body's y = 0 plane.
  ParticleTemplate plungerShape() const;
  Vec3 plungerCentre(double y) const { return {0.0f, static_cast<float>(y), 0.0f}; }
  void movePlunger(World& world, double simTime);
  /// Starts a motion of the plunger from where it is now: `direction` -1 down, +1 up, 0 stop.
  void startMove(double direction, double speed, double simTime);

  Config m_config;
  Phase m_phase = Phase::Settling;
  BodyId m_plunger;
  float m_granuleMass = 0.0f;
  double m_minSettleTime = 0.0;
  // The plunger's bottom: where it started its current motion, when, and in which direction.
  double m_moveFromY = 0.0;
  double m_moveStart = 0.0;
  double m_direction = 0.0;  // -1 down, +1 up, 0 parked
  double m_speed = 0.0;      // m/s
  double m_bottomY = 0.0;    // bottom face now, m
  double m_contactY = 0.0;   // bottom face where the experiment starts, m
  double m_height = 0.0;     // pile height there, m
  double m_maxStrain = 0.0;
  double m_residualStrain = 0.0;
  double m_peakStress = 0.0;
  bool m_touched = false;
  std::size_t m_turn = 0;
  std::vector<std::array<double, 2>> m_curve;
  Snapshot m_atRest;
  Snapshot m_atPeak;
};

}  // namespace sandphys::scenes
