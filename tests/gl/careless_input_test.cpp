// Inputs that a careless or hostile user gives a World (issue 18): each is refused with a
// sandphys::Error naming the field, the value and the limit, before anything is allocated or
// changed, or (a frame far too long) handled without losing the frame.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::errorMessageOf;

#define EXPECT_MESSAGE_HAS(message, text) \
  EXPECT_NE((message).find(text), std::string::npos) << (message)

TEST(CarelessInput, AMovedFromWorldRefusesEveryCallByName) {
  testing::TestWorld w;
  w.addGranule({0, 1, 0});
  World moved = std::move(*w);
  EXPECT_EQ(moved.bodyCount(), 1u);
  World& old = *w;
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.bodyCount(); }), "moved from");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.step(1.0f / 60.0f); }), "moved from");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.readBodies(); }), "moved from");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.readContacts(); }), "moved from");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.addCollider(Plane{}); }), "moved from");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { old.settings(); }), "moved from");
  // Assigned again, it works.
  old = std::move(moved);
  EXPECT_EQ(old.bodyCount(), 1u);
}

TEST(CarelessInput, AFrameOfMoreSubstepsThanAnIntegerHoldsRunsTheCap) {
  testing::TestWorld w;
  // 1e30 s is about 1e35 substeps: the count must not wrap to nothing.
  const StepReport report = w->step(1e30f);
  EXPECT_EQ(report.substeps, w->settings().maxSubstepsPerFrame);
  EXPECT_GT(report.droppedTime, 1e29f);
  EXPECT_EQ(w->step(1.0f / 60.0f).substeps,
            std::uint32_t(std::floor((1.0 / 60.0) / w->timeStep())));
}

TEST(CarelessInput, AHugeRoughFloorIsCountedBeforeItIsBuilt) {
  testing::TestWorld w;
  // 1000 m at 2 cm: about 7.9e9 particles, which would take hundreds of GB if built.
  const std::string message =
      errorMessageOf([&] { w->addRoughFloor(RoughFloor{.radius = 1000.0f}); });
  EXPECT_MESSAGE_HAS(message, "exceeds WorldSettings.maxParticles = 1024");
  // Half extents give the same, and a floor that fits still fits, to the particle.
  EXPECT_THROW(w->addRoughFloor(RoughFloor{.halfExtentX = 1000.0f, .halfExtentZ = 1000.0f}),
               CapacityExceeded);
  EXPECT_THROW(w->addRoughFloor(RoughFloor{.halfExtentX = 1e30f, .halfExtentZ = 1e30f}),
               InvalidArgument);  // beyond float resolution (below)
  EXPECT_EQ(w->bodyCount(), 0u);
  const BodyId floor = w->addRoughFloor(RoughFloor{.radius = 0.2f});
  EXPECT_TRUE(floor.isValid());
  // The lattice points within 10 spacings of the centre: counted by hand, 317.
  EXPECT_EQ(w->particleCount(), 317u);
  // A rectangle reaches the edge asked for, though 45 d in float metres is a hair under 45
  // spacings: 91 columns.
  const float d = w->settings().particleDiameter;
  w->addRoughFloor(
      RoughFloor{.center = {0.0f, 0.5f, 0.0f}, .halfExtentX = 45 * d, .halfExtentZ = 0.5f * d});
  EXPECT_EQ(w->particleCount(), 317u + 91u);
}

TEST(CarelessInput, HugeBlocksAndEmittersAreCountedBeforeTheyAreBuilt) {
  testing::TestWorld w;
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addGranules(GranuleBlock{.countX = 1000, .countY = 1000, .countZ = 1000});
                     }),
                     "adding 1000000000 bodies to 0 exceeds WorldSettings.maxBodies = 256");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addGranules(GranuleBlock{
                           .countX = 0xffffffffu, .countY = 0xffffffffu, .countZ = 0xffffffffu});
                     }),
                     "exceeds WorldSettings.maxBodies = 256");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addEmitter(EmitterSettings{.halfExtentX = 1e6f, .halfExtentZ = 1e6f});
                     }),
                     "EmitterSettings.halfExtentX/Z (lattice slots)");
  EXPECT_EQ(w->bodyCount(), 0u);
}

TEST(CarelessInput, ATemplateThatWouldPutNaNIntoTheWorldIsRefused) {
  testing::TestWorld w;
  const WorldSettings& s = w->settings();
  const ParticleTemplate good = tetrahedronTemplate(s.particleDiameter, s.material.density);

  ParticleTemplate nanOffset = good;
  nanOffset.offsets[2].y = std::nanf("");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addBody(nanOffset, BodyDesc{.position = {0, 1, 0}});
                     }),
                     "ParticleTemplate.offsets[2].y = nan");

  ParticleTemplate zeroRotation = good;
  zeroRotation.principalRotation = {0, 0, 0, 0};
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addBody(zeroRotation, BodyDesc{.position = {0, 1, 0}});
                     }),
                     "ParticleTemplate.principalRotation (squared norm) = 0");

  ParticleTemplate shortRadius = good;
  shortRadius.boundingRadius = 0.1f * good.boundingRadius;
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addBody(shortRadius, BodyDesc{.position = {0, 1, 0}});
                     }),
                     "ParticleTemplate.boundingRadius");
  EXPECT_EQ(w->bodyCount(), 0u);
  w->addBody(good, BodyDesc{.position = {0, 1, 0}});
  EXPECT_EQ(w->bodyCount(), 1u);
}

TEST(CarelessInput, ASnapshotThatWouldPutNaNIntoTheWorldIsRefusedAndChangesNothing) {
  testing::TestWorld w;
  w.addFloor();
  w.addGranule({0, 0.1f, 0});
  w.simulate(0.01);
  const WorldSnapshot good = w->readSnapshot();
  const std::uint64_t hash = w->readStateHash();

  const std::pair<std::function<void(WorldSnapshot&)>, std::string> cases[] = {
      {[](WorldSnapshot& s) { s.bodies[0].position[1] = std::nanf(""); },
       "WorldSnapshot.bodies[0].position.y = nan"},
      {[](WorldSnapshot& s) {
         s.bodies[0].principalOrientation = {0, 0, 0, 0};
       },
       "WorldSnapshot.bodies[0].principalOrientation (squared norm) = 0"},
      {[](WorldSnapshot& s) { s.bodies[0].angularVelocity[2] = INFINITY; },
       "WorldSnapshot.bodies[0].angularVelocity.z = inf"},
      {[](WorldSnapshot& s) { s.simulatedTime = std::nan(""); },
       "WorldSnapshot.simulatedTime = nan"},
      {[](WorldSnapshot& s) { s.unsteppedTime = -1.0; }, "WorldSnapshot.unsteppedTime = -1"},
      {[](WorldSnapshot& s) {
         s.contacts[0].pairs[3] = 1;
         s.contacts[0].slots[0][0] = std::bit_cast<std::uint32_t>(std::nanf(""));
       },
       "WorldSnapshot.contacts[0].slots[0] spring.x = nan"},
  };
  for (const auto& [damage, expected] : cases) {
    WorldSnapshot bad = good;
    damage(bad);
    EXPECT_MESSAGE_HAS(errorMessageOf([&] { w->restoreSnapshot(bad); }), expected);
    EXPECT_EQ(w->readStateHash(), hash) << expected;
  }
}

// With rolling friction the rolling springs are checked too.
TEST(CarelessInput, ASnapshotWithANaNRollingSpringIsRefusedAndChangesNothing) {
  WorldSettings settings = testing::smallSettings();
  settings.material.rollingFriction = 0.1f;
  testing::TestWorld w(settings);
  w.addFloor();
  w.addGranule({0, 0.1f, 0});
  w.simulate(0.01);
  WorldSnapshot bad = w->readSnapshot();
  const std::uint64_t hash = w->readStateHash();
  ASSERT_FALSE(bad.rolling.empty());
  bad.rolling[0].springs[0][1] = std::bit_cast<std::uint32_t>(std::nanf(""));
  EXPECT_MESSAGE_HAS(errorMessageOf([&] { w->restoreSnapshot(bad); }),
                     "WorldSnapshot.rolling[0].springs[0].y = nan");
  EXPECT_EQ(w->readStateHash(), hash);
}

TEST(CarelessInput, PositionsBeyondFloatResolutionAreRefused) {
  testing::TestWorld w;
  const WorldSettings& s = w->settings();
  const ParticleTemplate granule = tetrahedronTemplate(s.particleDiameter, s.material.density);
  // d = 2 cm: a float tells 0.01 d apart up to 0.01 * 0.02 * 2^23 = 1678 m.
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addBody(granule, BodyDesc{.position = {1e7f, 0, 0}});
                     }),
                     "BodyDesc.position (farthest coordinate, m) = 1");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addGranules(GranuleBlock{.center = {0, 0, -1e7f}, .countX = 2});
                     }),
                     "GranuleBlock.center");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addRoughFloor(RoughFloor{.center = {0, 2000, 0}, .radius = 0.1f});
                     }),
                     "RoughFloor.center");
  EXPECT_EQ(w->bodyCount(), 0u);
  const BodyId id = w->addBody(granule, BodyDesc{.position = {1000, 0, 0}});
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->setBodyState(id, BodyDesc{.position = {0, 5000, 0}});
                     }),
                     "must be <= 1677.722 m");
}

TEST(CarelessInput, AThinWallMovingFastEnoughToBeTunnelledIsRefused) {
  testing::TestWorld w;
  // At rest or slow, a cylinder is accepted; at 20 m/s a granule's particle meeting it would
  // overlap it by more than half a diameter.
  const ColliderId id = w->addCollider(Cylinder{.radius = 0.2f, .height = 0.3f});
  w->setCollider(id, Cylinder{.radius = 0.2f, .height = 0.3f, .motion = {.velocity = {1, 0, 0}}});
  EXPECT_MESSAGE_HAS(
      errorMessageOf([&] {
        w->setCollider(
            id, Cylinder{.radius = 0.2f, .height = 0.3f, .motion = {.velocity = {20, 0, 0}}});
      }),
      "ColliderMotion (surface speed, m/s) = 20");
  EXPECT_MESSAGE_HAS(errorMessageOf([&] {
                       w->addCollider(Funnel{.motion = {.angularVelocity = {0, 0, 50}}});
                     }),
                     "thin wall (cylinder, funnel)");
  EXPECT_EQ(w->colliders().size(), 1u);
}

TEST(CarelessInput, BodiesPlacedInsideSomethingAreReportedAtTheFirstStep) {
  const float d = testing::smallSettings().particleDiameter;
  const GranuleBlock block{.center = {0, 0.1f, 0}, .countX = 3, .countY = 2, .countZ = 3};
  // Well placed, above the floor: nothing to report, before or after a second step.
  {
    testing::TestWorld w;
    w.addFloor();
    w->addGranules(block);
    const StepReport report = w->step(1.0f / 60.0f);
    EXPECT_EQ(report.initialOverlaps.particles, 0u);
    EXPECT_FALSE(report.initialOverlaps.body.isValid());
  }
  // Half below the floor.
  {
    testing::TestWorld w;
    const ColliderId floor = w.addFloor(0.12f);
    w->addGranules(block);
    const InitialOverlaps found = w->step(1.0f / 60.0f).initialOverlaps;
    EXPECT_GT(found.particles, 20u);
    EXPECT_GT(found.worstOverlap, 0.5f * d);
    EXPECT_EQ(found.collider.index, floor.index);
    EXPECT_FALSE(found.otherBody.isValid());
    // Reported once: the next step checks nothing.
    EXPECT_EQ(w->step(1.0f / 60.0f).initialOverlaps.particles, 0u);
  }
  // Inside a solid box, and a second block on top of the first.
  {
    testing::TestWorld w;
    w.addFloor();
    w->addCollider(
        Box{.center = {0.5f, 0.1f, 0}, .halfExtents = {0.05f, 0.05f, 0.05f}, .inside = false});
    const BodyId inBox = w.addGranule({0.5f, 0.1f, 0});
    const InitialOverlaps boxed = w->step(1.0f / 60.0f).initialOverlaps;
    EXPECT_EQ(boxed.particles, 4u);
    EXPECT_EQ(boxed.body.index, inBox.index);
    EXPECT_EQ(boxed.collider.index, 1u);
    const BodyRange first = w->addGranules(block);
    w->step(1.0f / 60.0f);
    GranuleBlock onTop = block;
    onTop.center.x += 0.01f;
    const BodyRange second = w->addGranules(onTop);
    const InitialOverlaps stacked = w->step(1.0f / 60.0f).initialOverlaps;
    EXPECT_GT(stacked.particles, 20u);
    EXPECT_TRUE(second.contains(stacked.body));
    EXPECT_LE(stacked.otherBody.index, first[first.size() - 1].index);
    EXPECT_FALSE(stacked.collider.isValid());
  }
}

}  // namespace
}  // namespace sandphys
