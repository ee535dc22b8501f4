#pragma once

#include "sandphys/settings.h"

namespace sandphys {

/// The contact law of a World, derived once from its settings; the same numbers go to the
/// shaders (docs/architecture.md, "contacts"). Normal force for both laws (paper eq. 9, with the
/// damping exponent of Tsuji et al. so that the restitution does not depend on impact speed):
///   F_n = k_n ξ^{3/2} + γ_n ξ^{1/4} ξ',  γ_n = c(e) · sqrt(m* k_n),  F_n >= 0.
/// ContactLaw::HertzMindlin: tangential spring δ with history, k_t = k_t0 ξ^{1/2},
///   F_t = -k_t δ - η_t v_t,  η_t = γ_n ξ^{1/4},  |F_t| <= μ F_n (slip resets δ to the cap),
/// both at the contact point; m* from the two bodies' masses, shared by the n contacts that join
/// them. ContactLaw::PaperViscous (eq. 10): F_s = -min(μ F_n, γ_s |v_s|) v_s / |v_s| at the
/// particle centre, m* from particle masses, ξ capped at d/10.
struct ContactModel {
  ContactLaw law = ContactLaw::HertzMindlin;
  float radius = 0.0f;               ///< particle radius r = d/2, m
  float particleMass = 0.0f;         ///< mass of one sand particle, kg
  float granuleMass = 0.0f;          ///< mass of one granule (4 particles), kg
  float stiffnessGrain = 0.0f;       ///< k_n grain-grain = 4/3 E* sqrt(r/2), N/m^{3/2}
  float stiffnessWall = 0.0f;        ///< k_n grain-rigid surface = 4/3 E*_wall sqrt(r), N/m^{3/2}
  float shearStiffnessGrain = 0.0f;  ///< k_t0 grain-grain = 8 G* sqrt(r/2), N/m^{3/2}
  float shearStiffnessWall = 0.0f;   ///< k_t0 grain-rigid surface = 8 G*_wall sqrt(r), N/m^{3/2}
  float dampingFactorGrain = 0.0f;   ///< c(e) for the sand's restitution, dimensionless
  float tangentialDamping = 0.0f;    ///< PaperViscous: γ_s in N·s/m (resolved from automatic)
  /// PaperViscous: the overlap cap ξ_max = d/10, m. HertzMindlin has no cap (infinity).
  float maxOverlap = 0.0f;
  /// Closed-form peak overlap (undamped Hertz) of a granule meeting another granule head-on
  /// (m* = half a granule) and a static particle (m* = a granule) at maxSpeed, and a rigid wall
  /// (m* = a granule) at the fastest a particle moves, kGuardParticleSpeed · maxSpeed, m.
  /// HertzMindlin refuses settings where these let a grain pass through.
  float peakOverlapGrain = 0.0f;
  float peakOverlapWall = 0.0f;
  float peakOverlapFixedParticle = 0.0f;
  float timeStep = 0.0f;     ///< resolved substep, s
  float contactTime = 0.0f;  ///< t_n at maxSpeed for a grain-grain impact, s
  /// Skin of the neighbour lists, m (WorldSettings::listSkin, or the rule stated there).
  float listSkin = 0.0f;
  /// Near skin of the lists, m: kListNearSkinFraction · listSkin (settings.h).
  float listNearSkin = 0.0f;

  /// Builds and validates the model; throws InvalidArgument naming the field, value and limit.
  static ContactModel fromSettings(const WorldSettings& settings);
};

/// Overlaps, in particle diameters, of a single Hertz contact whose impact energy lets a grain
/// pass through what it meets (docs/architecture.md, "no force cap"): a particle slips into the
/// triangle of a granule's face at 1 - 1/sqrt(3) (counted as one contact: conservative), through
/// a thin wall (cylinder, funnel) once its centre crosses it at 1/2, and into the hole of a
/// square lattice of static particles of spacing s, whose four particles resist together, when it
/// has four times the energy of one contact at 1 - s/(d sqrt(2)): 4^{2/5} (1 - s/(d sqrt(2))); into
/// the hole of a sampled surface (sampleMesh at spacing h: no point farther than h/sqrt(3) from a
/// sample) when it has three times the energy of one contact at 1 - h/(d sqrt(3)):
/// 3^{2/5} (1 - h/(d sqrt(3))).
inline constexpr double kGrainPassOverlap = 0.42264973;  // 1 - 1/sqrt(3)
inline constexpr double kThinWallPassOverlap = 0.5;
double floorPassOverlap(double spacingOverDiameter);
double surfacePassOverlap(double gapOverDiameter);

/// The speed guard bounds a body's speed and the speed of its rim about its centre each by
/// maxSpeed, so a particle may move at up to twice maxSpeed: the speed a thin wall is checked at.
inline constexpr double kGuardParticleSpeed = 2.0;

/// The Young's modulus (Pa) at which two granules meeting head-on at maxSpeed
/// (ContactModel::peakOverlapGrain) overlap by `peakOverlap` (m), the other settings as given:
/// the peaks scale as E^{-2/5}. Up to 0.3 d it also passes every check of
/// ContactLaw::HertzMindlin (thin walls, a granule's face, a RoughFloor of spacing d). Throws
/// InvalidArgument for settings that are invalid otherwise.
double youngsModulusForPeakOverlap(const WorldSettings& settings, double peakOverlap);

/// Peak overlap of an undamped Hertz impact (m): (5 m* v² / (4 k_n))^{2/5}, from ½ m* v² =
/// 2/5 k_n ξ^{5/2}. Damping only lowers it.
double hertzPeakOverlap(double effectiveMass, double stiffness, double speed);

/// c(e): the dimensionless damping factor that gives restitution e for the Hertz law with
/// ξ^{1/4} damping (velocity independent). e in (0, 1]; c(1) = 0.
double hertzDampingFactor(double restitution);

/// Duration of a Hertz impact with damping factor c between bodies of effective mass m* (kg)
/// and stiffness k_n (N/m^{3/2}) at approach speed v (m/s): t_n = τ(c) · (m*² / (k_n² v))^{1/5}.
double hertzContactTime(double effectiveMass, double stiffness, double dampingFactor, double speed);

/// Static Hertz overlap (m) under a normal load (N): ξ = (load / k_n)^{2/3}.
double hertzRestingOverlap(double load, double stiffness);

}  // namespace sandphys
