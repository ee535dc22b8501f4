// The GPU step against closed forms, in the manner of Chrono's DEM unit tests: resting Hertz
// overlap, head-on impact (restitution and contact time), sliding under friction, free fall,
// torque-free spin.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::TestWorld;

// Orientation that turns the template's vertex (1, 1, 1)/√3 to +y: the opposite face lies flat.
Quat faceDown() {
  // Rotation about axis (1,1,1) x (0,1,0) = (-1, 0, 1)/√2 by acos(1/√3).
  const double angle = std::acos(1.0 / std::sqrt(3.0));
  const double s = std::sin(angle / 2.0) / std::sqrt(2.0);
  return {float(std::cos(angle / 2.0)), float(-s), 0.0f, float(s)};
}

double weightOfGranule(const World& w) {
  return tetrahedronTemplate(w.settings().particleDiameter, w.settings().material.density).mass *
         -w.settings().gravity.y;
}

TEST(ClosedForm, GranuleRestsAtTheHertzOverlapOfItsWeight) {
  TestWorld w;
  w.addFloor(0.0f);
  const float d = w->settings().particleDiameter;
  // Face down, just touching: three particles share the weight.
  const float faceHeight = d * std::sqrt(6.0f) / 12.0f;  // centre to face = circumradius / 3
  w.addGranule({0.0f, 0.5f * d + faceHeight + 1e-4f, 0.0f}, faceDown());
  w.simulate(0.4);
  const double expected =
      hertzRestingOverlap(weightOfGranule(*w) / 3.0, w->contactModel().stiffnessWall);
  auto particles = w->readParticles();
  ASSERT_EQ(particles.size(), 4u);
  int touching = 0;
  for (const auto& p : particles) {
    double overlap = 0.5 * d - p.position.y;
    if (overlap <= 0.0) continue;
    ++touching;
    EXPECT_NEAR(overlap, expected, 0.02 * expected) << "Hertz overlap for a third of the weight";
  }
  EXPECT_EQ(touching, 3);
  EXPECT_LT(std::abs(w->readBodies()[0].velocity.y), 1e-3f);
}

TEST(ClosedForm, HeadOnImpactHasTheSetRestitutionAndHertzContactTime) {
  WorldSettings s = testing::smallSettings();
  s.gravity = {0, 0, 0};
  s.material.restitution = 0.6f;
  TestWorld w(s);
  const float d = s.particleDiameter;
  const float v = 0.5f;  // each particle, towards the other
  w.addSphere({-0.5f * d - 2e-4f, 0, 0}, {v, 0, 0});
  w.addSphere({0.5f * d + 2e-4f, 0, 0}, {-v, 0, 0});
  // Step one substep at a time and count the substeps with a contact force.
  int contactSteps = 0;
  bool separated = false;
  for (int i = 0; i < 2000 && !separated; ++i) {
    w->substep(1);
    auto particles = w->readParticles();
    bool inContact = particles[0].force.x != 0.0f;
    if (inContact) ++contactSteps;
    separated = contactSteps > 0 && !inContact;
  }
  ASSERT_TRUE(separated);
  auto bodies = w->readBodies();
  const double restitution = (bodies[1].velocity.x - bodies[0].velocity.x) / (2.0 * v);
  EXPECT_NEAR(restitution, 0.6, 0.03 * 0.6);
  const ContactModel& m = w->contactModel();
  const double expected =
      hertzContactTime(0.5 * m.particleMass, m.stiffnessGrain, hertzDampingFactor(0.6), 2.0 * v);
  const double measured = contactSteps * double(w->timeStep());
  EXPECT_NEAR(measured, expected, 0.05 * expected);
  // Momentum is exchanged symmetrically.
  EXPECT_NEAR(bodies[0].velocity.x + bodies[1].velocity.x, 0.0, 1e-6);
}

TEST(ClosedForm, SlidingGranuleDeceleratesAtMuG) {
  const float mu = 0.3f;
  TestWorld w;
  w.addFloor(0.0f, {.friction = mu, .restitution = 0.5f});
  const float d = w->settings().particleDiameter;
  const float faceHeight = d * std::sqrt(6.0f) / 12.0f;
  // Settle first, then launch along x.
  BodyId g = w.addGranule({0.0f, 0.5f * d + faceHeight, 0.0f}, faceDown());
  w.simulate(0.3);
  BodyState rest = w->readBody(g);
  w->setBodyState(g, {rest.position, rest.orientation, {1.0f, 0, 0}, {}, Motion::Dynamic});
  w.simulate(0.05);  // past the launch transient
  BodyState a = w->readBody(g);
  w.simulate(0.2);
  BodyState b = w->readBody(g);
  ASSERT_GT(b.velocity.x, 0.05f) << "still sliding at the end of the window";
  const double deceleration = (a.velocity.x - b.velocity.x) / 0.2;
  const double g0 = -w->settings().gravity.y;
  EXPECT_NEAR(deceleration, mu * g0, 0.03 * mu * g0);
}

TEST(ClosedForm, FreeFallMatchesHalfGTSquared) {
  TestWorld w;
  const float y0 = 2.0f;
  BodyId g = w.addGranule({0, y0, 0});
  const std::uint32_t steps = 2000;
  w->substep(steps);
  const double t = steps * double(w->timeStep());
  const double g0 = -w->settings().gravity.y;
  BodyState s = w->readBody(g);
  // Semi-implicit Euler lands g·dt·t/2 below the exact parabola; allow that plus float round-off.
  const double exact = y0 - 0.5 * g0 * t * t;
  EXPECT_NEAR(s.position.y, exact, 0.5 * g0 * w->timeStep() * t + 1e-5);
  EXPECT_NEAR(s.velocity.y, -g0 * t, 1e-4 * g0 * t);
}

Vec3 angularMomentum(const ParticleTemplate& t, const BodyState& s) {
  // L = R I R^T ω with R from the principal frame; orientation read back is in the template's
  // frame, so rotate through principalRotation too.
  auto rotate = [](Quat q, Vec3 v, bool inverse) {
    if (inverse) q = {q.w, -q.x, -q.y, -q.z};
    // v' = v + 2w (u x v) + 2 u x (u x v)
    Vec3 u{q.x, q.y, q.z};
    auto cross = [](Vec3 a, Vec3 b) {
      return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    };
    Vec3 c = cross(u, v);
    Vec3 c2 = cross(u, c);
    return Vec3{v.x + 2 * (q.w * c.x + c2.x), v.y + 2 * (q.w * c.y + c2.y),
                v.z + 2 * (q.w * c.z + c2.z)};
  };
  Quat p = t.principalRotation;
  Quat q = s.orientation;
  Quat r{
      q.w * p.w - q.x * p.x - q.y * p.y - q.z * p.z, q.w * p.x + q.x * p.w + q.y * p.z - q.z * p.y,
      q.w * p.y - q.x * p.z + q.y * p.w + q.z * p.x, q.w * p.z + q.x * p.y - q.y * p.x + q.z * p.w};
  Vec3 local = rotate(r, s.angularVelocity, true);
  Vec3 l{local.x * t.principalInertia.x, local.y * t.principalInertia.y,
         local.z * t.principalInertia.z};
  return rotate(r, l, false);
}

TEST(ClosedForm, TorqueFreeSpinKeepsItsAngularMomentum) {
  WorldSettings s = testing::smallSettings();
  s.gravity = {0, 0, 0};
  TestWorld w(s);
  const float d = s.particleDiameter;
  // A tetrahedral granule (isotropic) and an L-shaped body of three particles (three different
  // moments), both spun about a skew axis: the second exercises the gyroscopic term.
  ParticleTemplate granule = tetrahedronTemplate(d, s.material.density);
  ParticleTemplate ell =
      makeParticleTemplate({{0, 0, 0}, {d, 0, 0}, {0, 1.5f * d, 0}}, d, s.material.density);
  const Vec3 spin{3.0f, -5.0f, 7.0f};  // rad/s: a rim speed well under the speed guard
  BodyId a = w->addBody(granule, {{0, 0, 0}, {}, {}, spin, Motion::Dynamic});
  BodyId b = w->addBody(ell, {{1, 0, 0}, {}, {}, spin, Motion::Dynamic});
  const Vec3 la0 = angularMomentum(granule, w->readBody(a));
  const Vec3 lb0 = angularMomentum(ell, w->readBody(b));
  w->substep(1000);
  const Vec3 la = angularMomentum(granule, w->readBody(a));
  const Vec3 lb = angularMomentum(ell, w->readBody(b));
  auto norm = [](Vec3 v) {
    return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
  };
  auto diff = [](Vec3 x, Vec3 y) { return Vec3{x.x - y.x, x.y - y.y, x.z - y.z}; };
  EXPECT_LT(norm(diff(la, la0)), 0.005 * norm(la0));
  EXPECT_LT(norm(diff(lb, lb0)), 0.005 * norm(lb0));
  // The L really precesses: its angular velocity changed direction (not a trivial test).
  EXPECT_GT(norm(diff(w->readBody(b).angularVelocity, spin)), 0.01 * norm(spin));
}

}  // namespace
}  // namespace sandphys
