#pragma once

// The Hertz impact with an adhesive tail: the normal force x^{3/2} + c x^{1/4} x' is not clamped at
// zero, so near the end of a contact the damping pulls, as LAMMPS's pair granular (damping tsuji)
// computes it. hertzDampingFactor (contact_model.h) is the clamped impact sandphys computes.

namespace sandphys::detail {

/// The c for which the adhesive impact rebounds with `restitution` (in (0, 1]).
double adhesiveHertzDampingFactor(double restitution);

/// The restitution of the adhesive impact with damping factor c (>= 0).
double adhesiveHertzRestitution(double dampingFactor);

}  // namespace sandphys::detail
