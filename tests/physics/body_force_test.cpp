// Bodies that are not granules: summed by a workgroup each (integrate_large_bodies.comp), and
// their sand force read back once per frame with World::takeBodyForces.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::gpu;
using testing::smallSettings;
using testing::TestWorld;

constexpr float kG = 9.81f;

// A flat square plate of n x n particles of diameter d, spacing d, in the xz plane.
ParticleTemplate plate(float d, int n, float density) {
  std::vector<Vec3> centres;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      centres.push_back({(i - 0.5f * (n - 1)) * d, 0.0f, (k - 0.5f * (n - 1)) * d});
    }
  }
  return makeParticleTemplate(centres, d, density);
}

// A granule resting off-centre on a kinematic plate presses it down with exactly its weight, and
// the torque about the plate's centre is the lever arm of that weight. The plate has 400
// particles, so the sums run through the workgroup reduction with many particles per thread.
TEST(BodyForce, KinematicPlateCarriesTheWeightOfAGranuleOnIt) {
  TestWorld w;
  const float d = w->settings().particleDiameter;
  const ParticleTemplate platform = plate(d, 20, w->settings().material.density);
  const BodyId plateId =
      w->addBody(platform, BodyDesc{.position = {0, 0, 0}, .motion = Motion::Kinematic});
  const float offset = 4.0f * d;
  const BodyId granule = w.addGranule({offset, 1.2f * d, 0.5f * d});
  w.simulate(0.4);  // lands and comes to rest
  (void)w->takeBodyForces();
  w.simulate(0.05);
  // The test world's granule is a body of its own (added with addBody), so it is listed too.
  const std::vector<BodyForce> forces = w->takeBodyForces();
  ASSERT_EQ(forces.size(), 2u);
  ASSERT_EQ(forces[0].body, plateId);
  ASSERT_EQ(forces[1].body, granule);
  const BodyForce& f = forces[0];
  const auto substeps = std::uint32_t(std::ceil(0.05 / w->timeStep()));
  EXPECT_NEAR(double(f.substeps), double(substeps), 1.0);
  // Newton's third law, substep by substep: the granule gets the opposite force.
  EXPECT_NEAR(forces[1].force.y, -f.force.y, 1e-4f * std::abs(f.force.y));
  const BodyState g = w->readBody(granule);
  ASSERT_LT(std::hypot(g.velocity.x, g.velocity.y, g.velocity.z), 1e-3f) << "not at rest";
  const float weight = tetrahedronTemplate(d, w->settings().material.density).mass * kG;
  const Vec3 mean = f.meanForce();
  EXPECT_NEAR(mean.y, -weight, 0.01f * weight);
  EXPECT_NEAR(mean.x, 0.0f, 0.01f * weight);
  EXPECT_NEAR(mean.z, 0.0f, 0.01f * weight);
  // r x F with r from the plate's centre to the granule's centre of mass, F = (0, -W, 0).
  const Vec3 torque = f.meanTorque();
  EXPECT_NEAR(torque.x, g.position.z * weight, 0.02f * weight * offset);
  EXPECT_NEAR(torque.z, -g.position.x * weight, 0.02f * weight * offset);
  EXPECT_NEAR(torque.y, 0.0f, 0.02f * weight * offset);
  // The plate is kinematic: the sand does not move it.
  const BodyState p = w->readBody(plateId);
  EXPECT_EQ(p.position.x, 0.0f);
  EXPECT_EQ(p.position.y, 0.0f);
  // The sums restart after each read.
  EXPECT_EQ(w->takeBodyForces()[0].substeps, 0u);
}

// A dynamic many-particle body falls freely at g (nothing touches it: zero sand force), and a
// kinematic one moves at its set velocity; both through the workgroup kernel.
TEST(BodyForce, LargeBodiesMoveByGravityOrByTheirSetVelocity) {
  TestWorld w;
  const float d = w->settings().particleDiameter;
  const ParticleTemplate platform = plate(d, 9, w->settings().material.density);
  const BodyId falling = w->addBody(platform, BodyDesc{.position = {0, 1, 0}});
  const BodyId carried = w->addBody(
      platform,
      BodyDesc{.position = {1, 1, 0}, .velocity = {0.5f, 0, 0}, .motion = Motion::Kinematic});
  const auto steps = std::uint32_t(400);
  w->substep(steps);
  const double t = double(steps) * w->timeStep();
  const BodyState a = w->readBody(falling);
  // Semi-implicit Euler: y = y0 - g dt^2 n(n+1)/2.
  const double dt = w->timeStep();
  const double expected = 1.0 - kG * dt * dt * double(steps) * double(steps + 1) / 2.0;
  EXPECT_NEAR(a.position.y, expected, 1e-4);
  EXPECT_NEAR(a.velocity.y, -kG * t, 1e-3);
  const BodyState b = w->readBody(carried);
  EXPECT_NEAR(b.position.x, 1.0 + 0.5 * t, 1e-4);
  EXPECT_NEAR(b.position.y, 1.0, 1e-6);
  for (const BodyForce& f : w->takeBodyForces()) {
    EXPECT_EQ(f.force.x, 0.0f);
    EXPECT_EQ(f.force.y, 0.0f);
    EXPECT_EQ(f.force.z, 0.0f);
    EXPECT_EQ(f.substeps, steps);
  }
}

// The same large body pushed by the same granules gives bit-identical sums on a second run.
TEST(BodyForce, SumsAreBitIdenticalFromRunToRun) {
  auto run = [] {
    TestWorld w;
    const float d = w->settings().particleDiameter;
    w->addBody(plate(d, 16, w->settings().material.density),
               BodyDesc{.position = {0, 0, 0}, .motion = Motion::Kinematic});
    w->addGranules(GranuleBlock{.center = {0.0f, 4.0f * d, 0.0f},
                                .countX = 4,
                                .countY = 2,
                                .countZ = 4,
                                .spacing = 2.4f * d,
                                .seed = 5});
    w.simulate(0.15);
    return w->takeBodyForces()[0];
  };
  const BodyForce first = run();
  const BodyForce second = run();
  EXPECT_NE(first.force.y, 0.0f) << "the granules never reached the plate";
  EXPECT_EQ(first.force.x, second.force.x);
  EXPECT_EQ(first.force.y, second.force.y);
  EXPECT_EQ(first.force.z, second.force.z);
  EXPECT_EQ(first.torque.x, second.torque.x);
  EXPECT_EQ(first.torque.y, second.torque.y);
  EXPECT_EQ(first.torque.z, second.torque.z);
}

// The list of bodies that are not granules has a fixed size; the one too many is refused with
// the limit named, and nothing is added.
TEST(BodyForce, TheLargeBodyLimitIsAClearErrorThatAddsNothing) {
  WorldSettings settings = smallSettings(5000);
  settings.maxParticles = 5000;
  TestWorld w(settings);
  for (int i = 0; i < 4096; ++i) w.addSphere({float(i % 64) * 0.05f, 1.0f, float(i / 64) * 0.05f});
  const std::uint32_t bodies = w->bodyCount();
  try {
    w.addSphere({0, 2, 0});
    FAIL() << "no error";
  } catch (const CapacityExceeded& error) {
    EXPECT_NE(std::string(error.what()).find("4096"), std::string::npos) << error.what();
  }
  EXPECT_EQ(w->bodyCount(), bodies);
  EXPECT_EQ(w->takeBodyForces().size(), 4096u);
}

// setBodyState keeps a body's motion; asking for another is an error that says so.
TEST(BodyForce, SetBodyStateRefusesAnotherMotion) {
  TestWorld w;
  const BodyId id = w.addSphere({0, 1, 0});
  try {
    w->setBodyState(id, BodyDesc{.position = {0, 2, 0}, .motion = Motion::Kinematic});
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("BodyDesc.motion"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace sandphys
