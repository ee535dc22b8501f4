// The two-way Bullet bridge: transparent without sand, a box resting on a sand bed, and the
// momentum the sand hands to a light box.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <sandphys/bullet/bridge.h>
#include <sandphys/bullet/owned_world.h>

#include "support/test_world.h"

namespace sandphys::bullet {
namespace {

using sandphys::testing::gpu;
using sandphys::testing::smallSettings;

bool sameTransform(const btTransform& a, const btTransform& b) {
  for (int i = 0; i < 3; ++i) {
    if (a.getOrigin()[i] != b.getOrigin()[i]) return false;
    for (int j = 0; j < 3; ++j) {
      if (a.getBasis()[i][j] != b.getBasis()[i][j]) return false;
    }
  }
  return true;
}

// With no sand anywhere, a coupled box falls, hits Bullet's ground and tumbles exactly as in a
// Bullet world stepped alone with the same fixed steps: the bridge adds nothing of its own.
TEST(Bridge, WithoutSandBulletRunsExactlyAsAlone) {
  btBoxShape box(btVector3(0.1f, 0.05f, 0.08f));
  btStaticPlaneShape ground(btVector3(0, 1, 0), 0);
  const btQuaternion tilt(btVector3(1, 0, 1).normalized(), 0.4f);
  OwnedWorld coupled, alone;
  const auto addBox = [&](OwnedWorld& world) {
    world.add(ground, 0.0f, btTransform::getIdentity());
    btRigidBody* b = world.add(box, 2.0f, btTransform(tilt, btVector3(0, 0.3f, 0)));
    b->setAngularVelocity(btVector3(1.0f, 3.0f, -2.0f));
    return b;
  };
  btRigidBody* coupledBox = addBox(coupled);
  btRigidBody* aloneBox = addBox(alone);

  WorldSettings settings = smallSettings(64);
  settings.maxParticles = 20000;
  // Soft and slow sand: a long substep, so that the empty sand world costs little per exchange.
  settings.material.youngsModulus = 5.0e5f;
  settings.maxSpeed = 1.0f;
  World sand(gpu(), settings);
  Bridge bridge(sand, coupled.dynamics());
  bridge.couple(coupledBox);
  const float frame = 1.0f / 60.0f;
  bool touched = false;
  int exchanges = 0;
  for (int f = 0; f < 30; ++f) {
    bridge.step(frame);
    // The same fixed steps as the bridge took this frame (it chooses them from the speeds).
    for (int i = 0; i < bridge.exchanges(); ++i) {
      alone.dynamics().stepSimulation(bridge.couplingStep(), 0);
    }
    exchanges += bridge.exchanges();
    ASSERT_TRUE(
        sameTransform(coupledBox->getCenterOfMassTransform(), aloneBox->getCenterOfMassTransform()))
        << "frame " << f;
    touched = touched || coupledBox->getCenterOfMassPosition().y() < 0.12f;
    EXPECT_EQ(bridge.coupled()[0].force.y, 0.0f);
  }
  EXPECT_TRUE(touched) << "the box never reached the ground";
  std::printf("%d exchanges in 30 frames\n", exchanges);
  // And the sand-side body went where Bullet put it.
  const BodyState mirrored = sand.readBody(bridge.coupled()[0].sandBody);
  EXPECT_NEAR(mirrored.position.y, coupledBox->getCenterOfMassPosition().y(), 0.02f);
}

TEST(Bridge, RefusesMismatchedGravityLightBodiesAndDoubleCoupling) {
  OwnedWorld physics;
  WorldSettings settings = smallSettings(64);
  settings.maxParticles = 20000;
  World sand(gpu(), settings);
  physics.dynamics().setGravity(btVector3(0, -9.0f, 0));
  try {
    Bridge bridge(sand, physics.dynamics());
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("gravity"), std::string::npos) << error.what();
  }
  physics.dynamics().setGravity(btVector3(0, -9.81f, 0));
  Bridge bridge(sand, physics.dynamics());
  btBoxShape pebble(btVector3(0.02f, 0.02f, 0.02f));
  btRigidBody* light =
      physics.add(pebble, 0.01f, btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)));
  try {
    bridge.couple(light);
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("lighter than"), std::string::npos) << error.what();
  }
  EXPECT_EQ(sand.bodyCount(), 0u);
  btBoxShape box(btVector3(0.1f, 0.1f, 0.1f));
  btRigidBody* heavy =
      physics.add(box, 5.0f, btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)));
  bridge.couple(heavy);
  EXPECT_THROW(bridge.couple(heavy), InvalidArgument);
  EXPECT_EQ(sand.bodyCount(), 1u);
}

// A light wooden box set on a bed of sand sinks a little, then rests: Bullet moves it, the sand
// carries it. Over the last seconds it stays put and the mean sand force equals its weight.
// The box of BoxRestsOnASandBedCarriedByTheSandForce, with sleeping sand or without. At the
// end, what slept; then, with sleep, Bullet wakes the box and sends it sideways into the sand.
struct BedResult {
  std::uint32_t granulesAsleep = 0;   // at the end of the 5 s
  bool boxAsleepInBullet = false;     // Bullet had deactivated the box
  bool bridgeSawItAsleep = false;     // Bridge::Coupled::asleep
  std::size_t lastFramePushes = 0;    // what the bridge pushed in the last frame
  StepReport lastFrame;               // the sand's substeps in it, and those skipped as idle
  std::uint32_t asleepAfterKick = 0;  // granules asleep 0.1 s after the kick
  float kickSpeed = 0.0f;             // the box's speed then, m/s
};

BedResult boxOnSandBed(bool sleep) {
  WorldSettings settings = smallSettings(400);
  settings.sleep.enabled = sleep;
  settings.maxParticles = 400 * 4 + 4000;
  settings.maxSpeed = 1.0f;
  settings.material.youngsModulus = 5.0e5f;
  World sand(gpu(), settings);
  const float d = settings.particleDiameter;
  const float half = 7.0f * d;  // container half width
  sand.addCollider(Box{.center = {0, 0.25f, 0}, .halfExtents = {half, 0.25f, half}});
  sand.addGranules(GranuleBlock{.center = {0, 0.07f, 0},
                                .countX = 6,
                                .countY = 4,
                                .countZ = 6,
                                .spacing = 2.4f * d,
                                .seed = 11});
  const auto start = std::chrono::steady_clock::now();
  // The bed settles for 0.8 s: the lattice falls about a granule and its kinetic energy drops
  // from 0.4 J to under 1e-3 J (an occasional grain still slips; the bed never quite stops).
  sand.substep(std::uint32_t(std::ceil(0.8 / sand.timeStep())));
  const double bedEnergy = sand.readStats().kineticEnergy;
  float bedTop = 0.0f;
  for (const BodyState& b : sand.readBodies()) bedTop = std::max(bedTop, b.position.y);
  bedTop += 0.6124f * d + 0.5f * d;

  OwnedWorld physics;
  btBoxShape boxShape(btVector3(4.5f * d, 1.0f * d, 4.5f * d));
  const float density = 500.0f;  // wood
  const float mass = density * 9.0f * d * 2.0f * d * 9.0f * d;
  btRigidBody* box = physics.add(
      boxShape, mass, btTransform(btQuaternion::getIdentity(), btVector3(0, bedTop + 1.6f * d, 0)));
  Bridge bridge(sand, physics.dynamics());
  bridge.couple(box);

  const float frame = 1.0f / 60.0f;
  const float weight = mass * 9.81f;
  std::vector<float> heights;
  float fastest = 0.0f;  // largest vertical speed of the box over the last second, m/s
  double forceSum = 0.0;
  int forceFrames = 0;
  const int frames = 300;  // 5 s
  StepReport report;
  for (int f = 0; f < frames; ++f) {
    report = bridge.step(frame);
    heights.push_back(float(box->getCenterOfMassPosition().y()));
    if (f >= frames - 60)
      fastest = std::max(fastest, std::abs(float(box->getLinearVelocity().y())));
    if (f >= frames - 120) {
      forceSum += bridge.coupled()[0].force.y;
      ++forceFrames;
    }
    if (f % 60 == 59) {
      std::printf("t %.2f s: box y %.4f m (bed top %.4f), sand force %.3f N (weight %.3f N)\n",
                  (f + 1) * frame, heights.back(), bedTop, bridge.coupled()[0].force.y, weight);
    }
  }
  const double meanForce = forceSum / forceFrames;
  const float sink = bedTop + 1.0f * d - heights.back();
  // Static friction (ContactLaw::HertzMindlin) holds the bed under the load: in the last second
  // the box sinks less than a hundredth of a grain (under the paper's memoryless friction the
  // bed crept and the box never stopped).
  const float secondTwo = heights[59] - heights[119];
  const float lastSecond = heights[frames - 61] - heights.back();
  std::printf("largest vertical speed of the box in the last second %.2e m/s\n", fastest);
  std::printf(
      "bed KE before the box %.2e J; dt %.3g s; sink %.4f m = %.3f d; sank %.2e m in the "
      "second second, %.2e m in the last; mean force %.3f N = %.4f W; %.0f s wall\n",
      bedEnergy, double(sand.timeStep()), sink, sink / d, secondTwo, lastSecond, meanForce,
      meanForce / weight,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  EXPECT_NEAR(meanForce, weight, 0.05 * weight);
  EXPECT_LT(std::abs(lastSecond), 0.01f * d) << "the box does not come to rest";
  EXPECT_GT(sink, -0.5f * d) << "the box floats above the bed";
  EXPECT_LT(sink, 3.0f * d) << "the box sank through the bed";
  const btVector3 up = box->getCenterOfMassTransform().getBasis().getColumn(1);
  EXPECT_GT(up.y(), 0.99f) << "the box tipped over";
  BedResult r;
  r.granulesAsleep = sand.readStats().granulesAsleep;
  r.boxAsleepInBullet = !box->isActive();
  r.bridgeSawItAsleep = bridge.coupled()[0].asleep;
  r.lastFramePushes = bridge.pushes().size();
  r.lastFrame = report;
  if (sleep) {
    // Woken in Bullet (as another Bullet body hitting it would), it ploughs into the sand.
    box->activate(true);
    box->setLinearVelocity(btVector3(0.3f, 0, 0));
    for (int f = 0; f < 6; ++f) bridge.step(frame);
    r.asleepAfterKick = sand.readStats().granulesAsleep;
    r.kickSpeed = float(box->getLinearVelocity().x());
  }
  return r;
}

TEST(Bridge, BoxRestsOnASandBedCarriedByTheSandForce) {
  const BedResult r = boxOnSandBed(false);
  EXPECT_EQ(r.granulesAsleep, 0u);
  // Bullet may put the resting box to sleep: the sand's force on it no longer changes.
  std::printf("box asleep in Bullet at the end: %d\n", int(r.boxAsleepInBullet));
}

// The same on sleeping sand: the box rests, carried, with no sink, and once it is at rest the
// sand under it falls asleep again (the bridge sets the resting box as a calm kinematic body).
// Bullet's own deactivation of the resting box is allowed, and the bridge then stops pushing it;
// woken in Bullet and moving, the box wakes the sand it touches.
TEST(Bridge, BoxRestsOnASleepingSandBed) {
  const BedResult r = boxOnSandBed(true);
  std::printf(
      "granules asleep at the end: %u of 144; box asleep in Bullet %d (bridge %d), %zu pushes in "
      "the last frame; 0.1 s after Bullet sent it at 0.3 m/s: %u asleep, box at %.3f m/s\n",
      r.granulesAsleep, int(r.boxAsleepInBullet), int(r.bridgeSawItAsleep), r.lastFramePushes,
      r.asleepAfterKick, r.kickSpeed);
  std::printf("the last frame: %u of %u substeps skipped as idle\n", r.lastFrame.idleSubsteps,
              r.lastFrame.substeps);
  EXPECT_GE(r.granulesAsleep, 130u);  // nine in ten of the 144 granules
  EXPECT_TRUE(r.boxAsleepInBullet);
  EXPECT_TRUE(r.bridgeSawItAsleep);
  EXPECT_EQ(r.lastFramePushes, 0u);
  // The box sleeps in the sand too, with the sand around it: the frame runs no substep, and the
  // bridge hands Bullet the force it last read (the mean force above is the weight).
  EXPECT_EQ(r.lastFrame.idleSubsteps, r.lastFrame.substeps);
  // The sand it ploughs into wakes and holds it back.
  EXPECT_LT(r.asleepAfterKick + 10u, r.granulesAsleep);
  EXPECT_LT(r.kickSpeed, 0.3f);
}

// Sand thrown at a light free box in empty space (no gravity, no floor, no walls): whatever the
// sand loses, the box gains. The bridge hands each exchange's summed sand force to Bullet one
// exchange later, so the box's momentum lags the sand's by at most one exchange's impulse; once
// the contacts have ended, the two must agree.
TEST(Bridge, SandThrownAtALightBoxHandsItTheMomentumItLoses) {
  WorldSettings settings = smallSettings(100);
  settings.maxParticles = 100 * 4 + 4000;
  settings.gravity = {0.0f, 0.0f, 0.0f};
  settings.maxSpeed = 1.0f;
  settings.material.youngsModulus = 5.0e5f;
  World sand(gpu(), settings);
  const float d = settings.particleDiameter;
  const float speed = 0.5f;  // m/s, along +x
  // 4×4×4 granules 2.4 d apart, so they arrive at the box one layer after another.
  const float spacing = 2.4f * d;
  const float blockFront = -2.0f * d;
  sand.addGranules(GranuleBlock{.center = {blockFront - 1.5f * spacing, 0, 0},
                                .countX = 4,
                                .countY = 4,
                                .countZ = 4,
                                .spacing = spacing,
                                .velocity = {speed, 0, 0},
                                .seed = 5});
  const float granuleMass = tetrahedronTemplate(d, settings.material.density).mass;

  OwnedWorld physics;
  physics.dynamics().setGravity(btVector3(0, 0, 0));
  // A plate broadside to the stream, wide enough that every column of granules hits it, and as
  // heavy as 24 granules: a third of the sand's mass, so that it is thrown clearly.
  btBoxShape plateShape(btVector3(1.5f * d, 6.0f * d, 6.0f * d));
  const float mass = 24.0f * granuleMass;
  btRigidBody* plate = physics.add(
      plateShape, mass, btTransform(btQuaternion::getIdentity(), btVector3(1.5f * d, 0, 0)));
  Bridge bridge(sand, physics.dynamics());
  bridge.couple(plate);

  const auto sandMomentum = [&] {
    Vec3 p{};
    for (const BodyState& b : sand.readBodies()) {
      if (!b.granule || !b.alive) continue;
      p.x += granuleMass * b.velocity.x;
      p.y += granuleMass * b.velocity.y;
      p.z += granuleMass * b.velocity.z;
    }
    return p;
  };
  const Vec3 before = sandMomentum();
  const float frame = 1.0f / 60.0f;
  int quietFrames = 0;  // frames in a row without any sand force on the plate
  int frames = 0;
  int exchanges = 0;
  bool touched = false;
  // Until the sand has let go of the plate for good (a few frames without contact), at most 2 s.
  while (frames < 120 && quietFrames < 6) {
    bridge.step(frame);
    ++frames;
    exchanges += bridge.exchanges();
    const Vec3 force = bridge.coupled()[0].force;
    const bool contact = force.x != 0.0f || force.y != 0.0f || force.z != 0.0f;
    touched = touched || contact;
    quietFrames = touched && !contact ? quietFrames + 1 : 0;
    if (frames % 6 == 0) {
      std::printf("t %.2f s: plate vx %.4f m/s, sand force x %.4f N\n", frames * frame,
                  float(plate->getLinearVelocity().x()), force.x);
    }
  }
  const Vec3 after = sandMomentum();
  const btVector3 plateMomentum = mass * plate->getLinearVelocity();
  const float lost = before.x - after.x;
  const float gained = float(plateMomentum.x());
  std::printf(
      "after %.2f s (%d exchanges): sand momentum x %.5f -> %.5f kg m/s, lost %.5f; plate gained "
      "%.5f kg m/s (speed %.4f m/s); sideways sand %.2e %.2e, plate %.2e %.2e\n",
      frames * frame, exchanges, before.x, after.x, lost, gained,
      float(plate->getLinearVelocity().x()), after.y - before.y, after.z - before.z,
      float(plateMomentum.y()), float(plateMomentum.z()));
  ASSERT_TRUE(touched) << "the sand never reached the plate";
  EXPECT_EQ(quietFrames, 6) << "the sand was still touching the plate after 2 s";
  // The plate was thrown: it carries at least a fifth of the sand's momentum.
  EXPECT_GT(gained, 0.2f * before.x);
  EXPECT_NEAR(gained, lost, 0.1f * lost);
  // Sideways too (the granules glance off at angles): what the sand gained, the plate lost.
  EXPECT_NEAR(float(plateMomentum.y()), before.y - after.y, 0.1f * lost);
  EXPECT_NEAR(float(plateMomentum.z()), before.z - after.z, 0.1f * lost);
}

}  // namespace
}  // namespace sandphys::bullet
