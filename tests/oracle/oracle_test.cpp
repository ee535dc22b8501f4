#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "oracle/cpu_oracle.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

using oracle::CpuOracle;
using oracle::OracleBody;
using oracle::OracleCollider;
using oracle::OracleModel;
using oracle::OracleParticle;
using oracle::toDouble;
using oracle::Vec3d;

struct Pile {
  testing::TestWorld world{testing::smallSettings(300)};
  std::vector<OracleCollider> colliders;
  ParticleTemplate granule;
};

void buildPile(Pile& p, int substeps) {
  World& w = *p.world;
  const Plane floor{};
  const Box box{.center = {0, 0.25f, 0}, .halfExtents = {0.125f, 0.3f, 0.125f}, .inside = true};
  w.addCollider(floor);
  w.addCollider(box);
  p.colliders = {OracleCollider::from(floor), OracleCollider::from(box)};
  w.addGranules(GranuleBlock{.center = {0, 0.222f, 0}, .countX = 5, .countY = 9, .countZ = 5,
                             .velocity = {0, -1.0f, 0}, .seed = 7});
  p.granule = tetrahedronTemplate(w.settings().particleDiameter, w.settings().material.density);
  w.substep(substeps);
}

std::vector<OracleBody> oracleBodies(const World& w, const ParticleTemplate& shape) {
  std::vector<OracleBody> out;
  for (const BodyState& s : w.readBodies()) out.push_back(OracleBody::from(s, shape, Motion::Dynamic));
  return out;
}

double roundOffAllowance(const oracle::OracleContact& c, double overlapError) {
  const double eps = 0x1p-24;
  const double xi = std::max(c.overlap, overlapError);
  const double gammaN = c.dampingFactor * std::sqrt(c.stiffness / c.invMassSum);
  const double xiDot = -c.relativeVelocity.dot(c.normal);
  const double velocityError = 4 * eps * c.relativeVelocity.norm();
  const double normal = 1.5 * c.stiffness * std::sqrt(xi) * overlapError +
                        gammaN * (0.25 * std::pow(xi, -0.75) * std::abs(xiDot) * overlapError +
                                  std::pow(xi, 0.25) * velocityError);
  return (1 + c.friction) * normal + c.tangentialDamping * velocityError + 8 * eps * c.force().norm();
}

struct ForceCheck { int failures = 0; double maxUse = 0, maxRel = 0, maxAbs = 0; int allowanceDominant = 0; };

ForceCheck checkForces(const CpuOracle& o, const std::vector<ParticleState>& gpu, double weight, bool print) {
  std::vector<OracleParticle> particles;
  for (const auto& g : gpu) {
    particles.push_back({g.body, toDouble(g.position), toDouble(g.velocity),
                         o.bodies()[g.body].particleInverseMass()});
  }
  auto contacts = o.findContacts(particles);
  std::vector<Vec3d> forces(particles.size(), Vec3d::Zero());
  std::vector<double> allowance(particles.size(), 0.0);
  const double overlapError = 4 * 0x1p-29;
  for (auto& c : contacts) { forces[c.particle] += c.force(); allowance[c.particle] += roundOffAllowance(c, overlapError); }
  ForceCheck r;
  for (std::size_t i = 0; i < forces.size(); ++i) {
    double err = (toDouble(gpu[i].force) - forces[i]).norm();
    double f = forces[i].norm();
    double tol = 1e-4 * std::max(f, 1e-3 * weight) + allowance[i];
    r.maxAbs = std::max(r.maxAbs, err);
    if (f > 1e-3 * weight) r.maxRel = std::max(r.maxRel, err / f);
    r.maxUse = std::max(r.maxUse, err / tol);
    if (allowance[i] > 1e-4 * std::max(f, 1e-3 * weight)) ++r.allowanceDominant;
    if (err > tol) { ++r.failures; if (print) std::printf("p %zu |F| %g err %g rel %g allow %g\n", i, f, err, err / f, allowance[i]); }
  }
  return r;
}

TEST(Oracle, Explore) {
  Pile p;
  auto t0 = std::chrono::steady_clock::now();
  buildPile(p, 2000);
  World& w = *p.world;
  auto t1 = std::chrono::steady_clock::now();
  std::printf("dt %g s, build %.2f s, contacts %zu\n", w.timeStep(), std::chrono::duration<double>(t1 - t0).count(), w.readContacts().size());
  const double weight = w.contactModel().particleMass * 9.81;
  auto gpuParticles = w.readParticles();
  auto bodies = oracleBodies(w, p.granule);
  CpuOracle o(OracleModel::fromWorld(w), bodies, p.colliders);
  auto r = checkForces(o, gpuParticles, weight, true);
  std::printf("forces: fail %d maxUse %g maxRel %g maxAbs %g allowanceDominant %d\n", r.failures, r.maxUse, r.maxRel, r.maxAbs, r.allowanceDominant);
  for (int which = 0; which < 3; ++which) {
    CpuOracle bad(OracleModel::fromWorld(w), bodies, p.colliders);
    if (which == 0) bad.model().friction *= 1.1;
    if (which == 1) bad.model().dampingFactorGrain *= 1.1;
    if (which == 2) bad.model().tangentialDamping *= 1.1;
    auto rb = checkForces(bad, gpuParticles, weight, false);
    std::printf("perturbed %d: fail %d maxUse %g\n", which, rb.failures, rb.maxUse);
  }

  std::vector<CpuOracle> oracles;
  for (int which = 0; which < 4; ++which) {
    oracles.emplace_back(OracleModel::fromWorld(w), bodies, p.colliders);
    if (which == 1) oracles.back().model().friction *= 1.1;
    if (which == 2) oracles.back().model().dampingFactorGrain *= 1.1;
    if (which == 3) oracles.back().model().tangentialDamping *= 1.1;
  }
  for (int k = 0; k < 5; ++k) {
    for (auto& o2 : oracles) o2.step(100);
    w.substep(100);
    auto gb = w.readBodies();
    for (int which = 0; which < 4; ++which) {
      double maxP = 0, maxV = 0, maxW = 0;
      for (std::size_t b = 0; b < gb.size(); ++b) {
        maxP = std::max(maxP, (toDouble(gb[b].position) - oracles[which].bodies()[b].position).norm());
        maxV = std::max(maxV, (toDouble(gb[b].velocity) - oracles[which].bodies()[b].velocity).norm());
        maxW = std::max(maxW, (toDouble(gb[b].angularVelocity) - oracles[which].bodies()[b].angularVelocity).norm());
      }
      std::printf("step %d model %d: pos %g vel %g spin %g\n", (k + 1) * 100, which, maxP, maxV, maxW);
    }
  }
}

}  // namespace
}  // namespace sandphys
