#pragma once

// The deck's words: numbers as LAMMPS reads them back exactly, and the contact law's coefficients
// (docs/lammps.md, "The contact law").

#include <string>

#include "sandphys/math.h"

namespace sandphys::detail {

/// A number with the 9 significant digits that give a float back bit for bit.
std::string lammpsNumber(double value);
/// "x y z".
std::string lammpsVector(Vec3 v);

/// The granular model of one kind of contact: `hertz kn e' tangential mindlin kt 1.0 mu damping
/// tsuji`, kn and kt LAMMPS's coefficients (sandphys's k_n and k_t0 over sqrt(R*): LAMMPS
/// multiplies them by the contact radius sqrt(R* ξ)), e' what damping tsuji must be given to
/// rebound at `restitution` (lammpsTsujiRestitution), then `rolling` (lammpsRolling).
std::string lammpsContact(double kn, double kt, double restitution, double friction,
                          const std::string& rolling = {});

/// The rolling model for sandphys's rolling friction μ_r (Material::rollingFriction): ` rolling
/// sds k_roll gamma_roll mu_r`, or nothing for μ_r = 0. sandphys's rolling spring has the
/// tangential spring's k_t = k_t0 sqrt(ξ) and the normal damping η = c(e) sqrt(m* k_n) ξ^{1/4};
/// LAMMPS takes constants, given here at `overlap` ξ (k_n, k_t0 sandphys's, m* the contact's
/// effective mass).
std::string lammpsRolling(double kn, double kt0, double dampingFactor, double effectiveMass,
                          double overlap, double rollingFriction);

/// The restitution to give LAMMPS's `damping tsuji` so that its impact rebounds with `e`.
double lammpsTsujiRestitution(double e);

}  // namespace sandphys::detail
