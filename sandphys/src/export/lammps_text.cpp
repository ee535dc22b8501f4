#include "export/lammps_text.h"

#include <cmath>
#include <cstdio>

#include "core/impact.h"

namespace sandphys::detail {

std::string lammpsNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::string lammpsVector(Vec3 v) {
  return lammpsNumber(v.x) + ' ' + lammpsNumber(v.y) + ' ' + lammpsNumber(v.z);
}

// LAMMPS turns e' into the damping factor with Tsuji's fit alpha(e') and lets the damping pull at
// the end of a contact (core/impact.h), so the e' it is given is not the e it produces: the
// factor that produces e in that impact, then the e' whose alpha is that factor (alpha falls from
// 1.27 at 0 to 0.0003 at 1).
double lammpsTsujiRestitution(double e) {
  const double factor = adhesiveHertzDampingFactor(e);
  auto alpha = [](double x) {
    return 1.2728 - 4.2783 * x + 11.087 * x * x - 22.348 * std::pow(x, 3) +
           27.467 * std::pow(x, 4) - 18.022 * std::pow(x, 5) + 4.8218 * std::pow(x, 6);
  };
  if (factor >= alpha(0.0)) return 0.0;
  if (factor <= alpha(1.0)) return 1.0;
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 48; ++i) {
    const double mid = 0.5 * (lo + hi);
    (alpha(mid) > factor ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Given as stiffnesses, not as hertz/material E e nu: fix wall/gran of LAMMPS 29 Sep 2021
// (Debian 12's) derives a wall's moduli from E and nu with other formulas than its pairs'.
std::string lammpsContact(double kn, double kt, double restitution, double friction,
                          const std::string& rolling) {
  return "hertz " + lammpsNumber(kn) + ' ' + lammpsNumber(lammpsTsujiRestitution(restitution)) +
         " tangential mindlin " + lammpsNumber(kt) + " 1.0 " + lammpsNumber(friction) +
         " damping tsuji" + rolling;
}

std::string lammpsRolling(double kn, double kt0, double dampingFactor, double effectiveMass,
                          double overlap, double rollingFriction) {
  if (rollingFriction == 0.0) return {};
  const double stiffness = kt0 * std::sqrt(overlap);
  const double damping = dampingFactor * std::sqrt(effectiveMass * kn) * std::pow(overlap, 0.25);
  return " rolling sds " + lammpsNumber(stiffness) + ' ' + lammpsNumber(damping) + ' ' +
         lammpsNumber(rollingFriction);
}

}  // namespace sandphys::detail
