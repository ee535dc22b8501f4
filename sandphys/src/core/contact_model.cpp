#include "sandphys/contact_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

#include "core/impact.h"
#include "core/overlap_check.h"
#include "core/validation.h"
#include "core/world_checks.h"

namespace sandphys {
namespace {

// The dimensionless impact x'' = -max(0, x^{3/2} + c x^{1/4} x'), x(0) = 0, x'(0) = 1, in units
// ξ0 = (m* v² / k_n)^{2/5} and ξ0 / v. Integrated with RK4 until the surfaces separate. With
// `adhesive`, the force is not clamped at zero (the damping pulls near the end, as LAMMPS's pair
// granular lets it) and the contact lasts until the overlap is gone.
struct ImpactResult {
  double restitution;
  double duration;
};

ImpactResult integrateImpact(double c, bool adhesive = false) {
  auto accel = [c, adhesive](double x, double v) {
    if (x <= 0.0) return 0.0;
    const double force = x * std::sqrt(x) + c * std::sqrt(std::sqrt(x)) * v;
    return adhesive ? -force : -std::max(0.0, force);
  };
  // The contact ends when the (non-adhesive) force vanishes on the way out: from then on the
  // bodies move apart freely, whatever overlap remains.
  auto released = [c, adhesive](double x, double v) {
    return !adhesive && v < 0.0 &&
           x * std::sqrt(x) + c * std::sqrt(std::sqrt(std::max(x, 0.0))) * v <= 0.0;
  };
  const double h = 2.0e-4;
  double x = 0.0;
  double v = 1.0;
  double t = 0.0;
  for (int i = 0; i < 10'000'000; ++i) {
    double k1x = v, k1v = accel(x, v);
    double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    double nx = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    double nv = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (nx <= 0.0 || released(nx, nv)) {
      // Released inside this step: interpolate the end of the contact linearly.
      double before = x * std::sqrt(x) + c * std::sqrt(std::sqrt(x)) * v;
      double after = nx <= 0.0 ? -before : nx * std::sqrt(nx) + c * std::sqrt(std::sqrt(nx)) * nv;
      double frac = nx <= 0.0 ? x / (x - nx) : before / (before - after);
      return {-(v + frac * (nv - v)), t + frac * h};
    }
    x = nx;
    v = nv;
    t += h;
  }
  return {0.0, t};
}

double requireRestitution(double e, const std::string& field) {
  detail::require(std::isfinite(e) && e > 0.0 && e <= 1.0, field, e, "must be in (0, 1]");
  return e;
}

// e(c) falls monotonically from 1 at c = 0; bisect.
double solveDampingFactor(double restitution, bool adhesive) {
  double lo = 0.0;
  double hi = 1.0;
  while (integrateImpact(hi, adhesive).restitution > restitution) hi *= 2.0;
  for (int i = 0; i < 48; ++i) {
    double mid = 0.5 * (lo + hi);
    (integrateImpact(mid, adhesive).restitution > restitution ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double hertzDampingFactor(double restitution) {
  requireRestitution(restitution, "restitution");
  if (restitution >= 1.0) return 0.0;
  static std::mutex mutex;
  static std::map<double, double> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(restitution); it != cache.end()) return it->second;
  double c = solveDampingFactor(restitution, false);
  cache[restitution] = c;
  return c;
}

namespace detail {

double adhesiveHertzDampingFactor(double restitution) {
  requireRestitution(restitution, "restitution");
  return restitution >= 1.0 ? 0.0 : solveDampingFactor(restitution, true);
}

double adhesiveHertzRestitution(double dampingFactor) {
  return integrateImpact(dampingFactor, true).restitution;
}

}  // namespace detail

double hertzContactTime(double effectiveMass, double stiffness, double dampingFactor,
                        double speed) {
  double tau = integrateImpact(dampingFactor).duration;
  return tau * std::pow(effectiveMass * effectiveMass / (stiffness * stiffness * speed), 0.2);
}

double hertzRestingOverlap(double load, double stiffness) {
  return std::pow(load / stiffness, 2.0 / 3.0);
}

double hertzPeakOverlap(double effectiveMass, double stiffness, double speed) {
  return std::pow(1.25 * effectiveMass * speed * speed / stiffness, 0.4);
}

double surfacePassOverlap(double gapOverDiameter) {
  // ½ m* v² = 3 · 2/5 k ξ_hole^{5/2} is a single contact's energy at 3^{2/5} ξ_hole.
  return std::pow(3.0, 0.4) * (1.0 - gapOverDiameter / std::numbers::sqrt3);
}

double floorPassOverlap(double spacingOverDiameter) {
  // ½ m* v² = 4 · 2/5 k ξ_hole^{5/2} is a single contact's energy at 4^{2/5} ξ_hole.
  return std::pow(4.0, 0.4) * (1.0 - spacingOverDiameter / std::numbers::sqrt2);
}

double youngsModulusForPeakOverlap(const WorldSettings& settings, double peakOverlap) {
  detail::requirePositive("peakOverlap", peakOverlap, "(m)");
  // The paper's law resolves the same peaks without refusing any.
  WorldSettings probe = settings;
  probe.contactLaw = ContactLaw::PaperViscous;
  const ContactModel m = ContactModel::fromSettings(probe);
  return settings.material.youngsModulus * std::pow(m.peakOverlapGrain / peakOverlap, 2.5);
}

namespace detail {

void requireNoPassThrough(const WorldSettings& s, double peakOverlap, double passOverlap,
                          const std::string& what) {
  const double d = s.particleDiameter;
  if (peakOverlap <= passOverlap * d) return;
  // ξ ∝ E^{-2/5} v^{4/5}: the E (or the speed) that brings the peak down to the limit.
  const double ratio = peakOverlap / (passOverlap * d);
  const double youngs = s.material.youngsModulus * std::pow(ratio, 2.5);
  const double speed = s.maxSpeed * std::pow(ratio, -1.25);
  throw InvalidArgument(
      "WorldSettings.material.youngsModulus = " + formatValue(s.material.youngsModulus) +
      " Pa is too soft for WorldSettings.maxSpeed = " + formatValue(s.maxSpeed) + " m/s: " + what +
      " would overlap by " + formatValue(peakOverlap / d) + " d (closed-form Hertz peak), past " +
      formatValue(passOverlap) + " d where it passes through; raise youngsModulus to at least " +
      formatValue(youngs) + " Pa or lower maxSpeed to " + formatValue(speed) +
      " m/s (ContactLaw::PaperViscous caps the overlap instead)");
}

}  // namespace detail

ContactModel ContactModel::fromSettings(const WorldSettings& s) {
  using detail::require;
  detail::checkSettingRanges(s);
  require(s.listSkin <= s.particleDiameter, "WorldSettings.listSkin", s.listSkin,
          "must be in [0, particleDiameter = " + detail::formatValue(s.particleDiameter) +
              "] m (0: derived from maxSpeed)");

  ContactModel m;
  m.law = s.contactLaw;
  const double d = s.particleDiameter;
  const double r = 0.5 * d;
  const double nu = s.material.poissonRatio;
  const double youngs = s.material.youngsModulus;
  const double eStar = youngs / (2.0 * (1.0 - nu * nu));
  const double eStarWall = youngs / (1.0 - nu * nu);
  // G = E / (2 (1 + ν)); G* = G / (2 (2 - ν)) for two equal grains, G / (2 - ν) against a rigid
  // surface.
  const double shear = youngs / (2.0 * (1.0 + nu));
  const double gStar = shear / (2.0 * (2.0 - nu));
  const double gStarWall = shear / (2.0 - nu);
  const double mass = s.material.density * std::numbers::pi * d * d * d / 6.0;
  m.radius = static_cast<float>(r);
  m.particleMass = static_cast<float>(mass);
  m.granuleMass = static_cast<float>(4.0 * mass);
  m.stiffnessGrain = static_cast<float>(4.0 / 3.0 * eStar * std::sqrt(0.5 * r));
  m.stiffnessWall = static_cast<float>(4.0 / 3.0 * eStarWall * std::sqrt(r));
  m.shearStiffnessGrain = static_cast<float>(8.0 * gStar * std::sqrt(0.5 * r));
  m.shearStiffnessWall = static_cast<float>(8.0 * gStarWall * std::sqrt(r));
  m.dampingFactorGrain = static_cast<float>(hertzDampingFactor(s.material.restitution));
  const bool paper = s.contactLaw == ContactLaw::PaperViscous;
  require(!paper || s.material.rollingFriction == 0.0f, "WorldSettings.material.rollingFriction",
          s.material.rollingFriction,
          "must be 0 with ContactLaw::PaperViscous: the paper's law acts at particle centres and "
          "turns no body at a contact");
  m.maxOverlap = paper ? static_cast<float>(0.1 * d) : std::numeric_limits<float>::infinity();

  // The peak overlaps of the stiffness check: two granules head-on, and a granule against a rigid
  // wall and against a static particle (a rough floor), all at maxSpeed.
  const double granule = 4.0 * mass;
  m.peakOverlapGrain =
      static_cast<float>(hertzPeakOverlap(0.5 * granule, m.stiffnessGrain, s.maxSpeed));
  m.peakOverlapWall = static_cast<float>(
      hertzPeakOverlap(granule, m.stiffnessWall, kGuardParticleSpeed * s.maxSpeed));
  m.peakOverlapFixedParticle =
      static_cast<float>(hertzPeakOverlap(granule, m.stiffnessGrain, s.maxSpeed));
  if (!paper) {
    // The check that asks the most first, so that the E (or speed) it names passes both.
    const bool grainFirst =
        m.peakOverlapGrain / kGrainPassOverlap >= m.peakOverlapWall / kThinWallPassOverlap;
    const auto grain = [&] {
      detail::requireNoPassThrough(s, m.peakOverlapGrain, kGrainPassOverlap,
                                   "a granule meeting another head-on at maxSpeed");
    };
    const auto wall = [&] {
      detail::requireNoPassThrough(
          s, m.peakOverlapWall, kThinWallPassOverlap,
          "a granule's particle meeting a thin wall (cylinder, funnel) at twice maxSpeed (the "
          "guard's limit for a spinning granule)");
    };
    if (grainFirst) {
      grain();
      wall();
    } else {
      wall();
      grain();
    }
  }

  // t_n: the shorter of a grain-grain (m* = m/2) and a grain-wall (m* = m) impact at maxSpeed.
  const double tGrain =
      hertzContactTime(0.5 * mass, m.stiffnessGrain, m.dampingFactorGrain, s.maxSpeed);
  const double tWall = hertzContactTime(mass, m.stiffnessWall, m.dampingFactorGrain, s.maxSpeed);
  m.contactTime = static_cast<float>(std::min(tGrain, tWall));
  const double limit = m.contactTime / kMinStepsPerContact;
  const double finest = m.contactTime / kMaxStepsPerContact;
  if (s.timeStep > 0.0f) {
    require(s.timeStep <= limit, "WorldSettings.timeStep", s.timeStep,
            "must be <= t_n / " + detail::formatValue(kMinStepsPerContact) + " = " +
                detail::formatValue(limit) +
                " s for this material (t_n = " + detail::formatValue(m.contactTime) +
                " s at maxSpeed " + detail::formatValue(s.maxSpeed) +
                " m/s); lower it, or lower youngsModulus or maxSpeed");
    require(s.timeStep >= finest, "WorldSettings.timeStep", s.timeStep,
            "must be >= t_n / " + detail::formatValue(kMaxStepsPerContact) + " = " +
                detail::formatValue(finest) +
                " s for this material (t_n = " + detail::formatValue(m.contactTime) +
                " s): a finer step resolves nothing more and only multiplies the cost");
    m.timeStep = s.timeStep;
  } else {
    m.timeStep = static_cast<float>(m.contactTime / s.stepsPerContact);
  }
  if (s.listSkin > 0.0f) {
    m.listSkin = s.listSkin;
  } else {
    const double travel = 2.0 * kListSkinSubsteps * s.maxSpeed * m.timeStep;
    m.listSkin = static_cast<float>(std::clamp(travel, kMinListSkin * d, kMaxListSkin * d));
  }
  m.listNearSkin = kListNearSkinFraction * m.listSkin;
  m.tangentialDamping = s.material.tangentialDamping > 0.0f
                            ? s.material.tangentialDamping
                            : static_cast<float>(0.25 * mass / m.timeStep);
  return m;
}

}  // namespace sandphys
