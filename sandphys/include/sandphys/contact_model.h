#pragma once

#include "sandphys/settings.h"

namespace sandphys {

/// The contact law of a World, derived once from its settings; the same numbers go to the
/// shaders. Normal force (paper eq. 9, with the damping exponent of Tsuji et al. so that the
/// restitution does not depend on impact speed):
///   F_n = k_n ξ^{3/2} + γ_n ξ^{1/4} ξ',  γ_n = c(e) · sqrt(m* k_n),  F_n >= 0,
/// friction (eq. 10): F_s = -min(μ F_n, γ_s |v_s|) v_s / |v_s|.
/// See docs/architecture.md, "contacts".
struct ContactModel {
  float radius = 0.0f;              ///< particle radius r = d/2, m
  float particleMass = 0.0f;        ///< mass of one sand particle, kg
  float stiffnessGrain = 0.0f;      ///< k_n grain-grain = 4/3 E* sqrt(r/2), N/m^{3/2}
  float stiffnessWall = 0.0f;       ///< k_n grain-rigid surface = 4/3 E*_wall sqrt(r), N/m^{3/2}
  float dampingFactorGrain = 0.0f;  ///< c(e) for the sand's restitution, dimensionless
  float tangentialDamping = 0.0f;   ///< γ_s in N·s/m (resolved from automatic)
  float maxOverlap = 0.0f;          ///< penetration guard ξ_max = d/10, m
  float timeStep = 0.0f;            ///< resolved substep, s
  float contactTime = 0.0f;         ///< t_n at maxSpeed for a grain-grain impact, s

  /// Builds and validates the model; throws InvalidArgument naming the field, value and limit.
  static ContactModel fromSettings(const WorldSettings& settings);
};

/// c(e): the dimensionless damping factor that gives restitution e for the Hertz law with
/// ξ^{1/4} damping (velocity independent). e in (0, 1]; c(1) = 0.
double hertzDampingFactor(double restitution);

/// Duration of a Hertz impact with damping factor c between bodies of effective mass m* (kg)
/// and stiffness k_n (N/m^{3/2}) at approach speed v (m/s): t_n = τ(c) · (m*² / (k_n² v))^{1/5}.
double hertzContactTime(double effectiveMass, double stiffness, double dampingFactor, double speed);

/// Static Hertz overlap (m) under a normal load (N): ξ = (load / k_n)^{2/3}.
double hertzRestingOverlap(double load, double stiffness);

}  // namespace sandphys
