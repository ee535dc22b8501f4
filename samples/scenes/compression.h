#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct CompressionConfig {
  float particleDiameter = 0.02f;
  float radius = 12.0f;
  std::uint32_t layers = 12;
  float plungerSpeed = 0.05f;  // m/s
  float maxStress = 20000.0f;  // Pa
  float preloadFraction = 0.5f;
  float friction = 0.5f;
  float youngsModulus = 0.0f;  // Pa
  float settleSpeed = 0.02f;   // m/s
  float maxSettleSeconds = 3.0f;
  float stepsPerContact = 10.0f;
  std::uint64_t seed = 1;
};

/// Uniaxial compression of a settled pile (Longmore et al. 2013, sections 6.1.1 and 6.1.3, Figs.
/// 17c and 21). A lattice of granules settles in a smooth cylinder on a rough floor (particle
/// centres at y = 0). A kinematic plunger, a disc of particles 0.75 d narrower than the cylinder,
/// comes down, presses the top flat with preload × maxStress and eases back to where the sand no
/// longer pushes; from there it loads the pile at plungerSpeed up to maxStress and unloads it to
/// zero stress. Stress (the plunger's force over the cross-section) against strain (its travel
/// over the pile's height) shows hysteresis and a residual strain. Every contact is read back
/// twice: at rest and at the peak.
class Compression final : public kit::SceneWith<CompressionConfig> {
 public:
  using SceneWith::SceneWith;

  /// Every contact at one moment, and the bodies then (for granule-level forces).
  struct Snapshot {
    double time = -1.0;  ///< s; negative until taken
    std::vector<ContactRecord> contacts;
    std::vector<BodyState> bodies;
  };

  std::string_view name() const override { return "compression"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Steers the plunger through its phases and records stress and strain.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_phase == Phase::Done; }
  std::string status() const override;
  /// Inside the cylinder, above the floor.
  bool contains(const Vec3& centre) const override;
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "stress_strain": [strain, stress Pa] per frame of the experiment (loading, then unloading),
  /// with max_strain (at the turn), residual_strain (where unloading brought the stress back to
  /// zero, or the last strain recorded if it never did) and recovered_fraction ((max − residual) /
  /// max; 0 before the turn).
  std::vector<SceneSeries> series() const override;
  SceneBounds bounds() const override;

  /// Index in the "stress_strain" points of the turn from loading to unloading.
  std::size_t turnIndex() const { return m_turn; }
  const Snapshot& atRest() const { return m_atRest; }
  const Snapshot& atPeak() const { return m_atPeak; }
  /// Granules of the lattice the pile is dropped from.
  std::uint64_t granules() const;

 private:
  enum class Phase { Settling, Approach, Preload, Easing, Loading, Unloading, Done };
  std::span<const kit::Param<Config>> table() const override;
  std::uint32_t latticeSide() const;
  double area() const;
  /// The plunger's face: a disc of particles in the body's y = 0 plane.
  std::vector<Vec3> plungerFace() const;
  /// The plunger drawn as a disc.
  SceneSurface plungerSurface(BodyId plunger, const ParticleTemplate& shape,
                              const std::vector<Vec3>& face) const;
  /// Enters `phase`, the plunger moving as it says from where it is.
  void enter(Phase phase, double simTime);
  double recoveredFraction() const;

  Phase m_phase = Phase::Settling;
  kit::SettleWait m_settle;
  float m_granuleMass = 0.0f;  // kg
  BodyId m_plunger;
  double m_bottomY = 0.0;  // the plunger's bottom face now, m
  double m_moveFromY = 0.0, m_moveStart = 0.0, m_velocity = 0.0;  // its motion: m, s, m/s
  double m_contactY = 0.0;  // the bottom face where the experiment starts, m
  double m_height = 0.0;    // the pile's height there, m
  double m_peakStress = 0.0, m_maxStrain = 0.0, m_residualStrain = 0.0;
  std::size_t m_turn = 0;
  std::vector<std::array<double, 2>> m_curve;
  Snapshot m_atRest;
  Snapshot m_atPeak;
};

}  // namespace sandphys::scenes
