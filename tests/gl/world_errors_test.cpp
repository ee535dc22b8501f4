// Misuse of a World throws sandphys::Error naming the field, the value and the limit, and loses
// nothing: a refused call leaves the world as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::errorMessageOf;

TEST(WorldErrors, CapacityExceededAddsNothing) {
  testing::TestWorld w(testing::smallSettings(10));
  w->addGranules(GranuleBlock{.center = {0, 1, 0}, .countX = 2, .countY = 2, .countZ = 2});
  std::string message = errorMessageOf([&] {
    w->addGranules(GranuleBlock{.center = {0, 2, 0}, .countX = 2, .countY = 2, .countZ = 1});
  });
  EXPECT_NE(message.find("maxBodies = 10"), std::string::npos) << message;
  EXPECT_EQ(w->bodyCount(), 8u);
  EXPECT_EQ(w->particleCount(), 32u);
  EXPECT_THROW(
      w->addGranules(GranuleBlock{.center = {0, 2, 0}, .countX = 3, .countY = 1, .countZ = 1}),
      CapacityExceeded);
  // reserve() is the explicit way to grow; afterwards the same call succeeds and the old
  // granules are still there.
  w->reserve(20, 80);
  w->addGranules(GranuleBlock{.center = {0, 2, 0}, .countX = 3, .countY = 1, .countZ = 1});
  EXPECT_EQ(w->bodyCount(), 11u);
  auto bodies = w->readBodies();
  EXPECT_NEAR(bodies[0].position.y, 1.0f - 0.5f * 0.048f, 0.01f);
}

TEST(WorldErrors, TooManyParticlesNamesTheLimit) {
  WorldSettings s = testing::smallSettings();
  s.maxParticles = 1u << 30;
  std::string message = errorMessageOf([&] { World w(testing::gpu(), s); });
  EXPECT_NE(message.find("WorldSettings.maxParticles = 1073741824"), std::string::npos) << message;
  EXPECT_NE(message.find("<= 2097152"), std::string::npos) << message;
}

TEST(WorldErrors, BadDescriptorsNameTheirField) {
  testing::TestWorld w;
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Cylinder{.radius = -1.0f});
            }).find("Cylinder.radius = -1"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Plane{.normal = {0, 0, 0}});
            }).find("Plane.normal"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Funnel{.halfAngle = 2.0f});
            }).find("Funnel.halfAngle = 2"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Box{.material = {.friction = -1.0f}});
            }).find("Box.material.friction"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Box{.material = {.restitution = 0.0f}});
            }).find("(0, 1]"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addGranules(GranuleBlock{.countX = 0});
            }).find("GranuleBlock.countX = 0"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addGranules(GranuleBlock{.spacing = 0.03f});
            }).find("GranuleBlock.spacing = 0.03"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addGranules(GranuleBlock{.center = {0, std::nanf(""), 0}});
            }).find("GranuleBlock.center.y = nan"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addEmitter(EmitterSettings{.rate = 0.0f});
            }).find("EmitterSettings.rate = 0"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addSink(Sink{.min = {1, 1, 1}, .max = {0, 0, 0}});
            }).find("Sink.max"),
            std::string::npos);
  EXPECT_NE(errorMessageOf([&] {
              w->addCollider(Plane{.motion = {.velocity = {0, std::nanf(""), 0}}});
            }).find("Plane.motion.velocity.y = nan"),
            std::string::npos);
  // A floor so sparse that a granule landing at maxSpeed would slip between its particles.
  EXPECT_NE(errorMessageOf([&] {
              w->addRoughFloor(RoughFloor{.radius = 0.1f, .spacing = 0.03f});
            }).find("RoughFloor of spacing 1.5 d"),
            std::string::npos);
  EXPECT_EQ(w->bodyCount(), 0u);
}

TEST(WorldErrors, ASnapshotWithoutItsContactHistoryIsRefused) {
  testing::TestWorld w;
  w.addGranule({0, 1, 0});
  WorldSnapshot snapshot = w->readSnapshot();
  ASSERT_EQ(snapshot.contacts.size(), 4u);
  snapshot.contacts.pop_back();
  const std::string message = errorMessageOf([&] { w->restoreSnapshot(snapshot); });
  EXPECT_NE(message.find("WorldSnapshot.contacts.size() = 3"), std::string::npos) << message;
  EXPECT_NE(message.find("must be 4"), std::string::npos) << message;
}

TEST(WorldErrors, StaleAndDefaultIdsAreRefused) {
  testing::TestWorld w;
  EXPECT_THROW(w->setBodyState(BodyId{}, BodyDesc{}), InvalidId);
  EXPECT_THROW(w->readBody(BodyId{5, 0}), InvalidId);
  BodyId id = w.addGranule({0, 1, 0});
  EXPECT_NO_THROW(w->readBody(id));
  EXPECT_THROW(w->readBody(BodyId{id.index, id.generation + 1}), InvalidId);
  EXPECT_THROW(w->removeEmitter(EmitterId{3}), InvalidId);
  EXPECT_THROW(w->setCollider(ColliderId{7}, Plane{}), InvalidId);
}

TEST(WorldErrors, StepNeverThrowsOnOddFrameTimes) {
  testing::TestWorld w;
  EXPECT_EQ(w->step(std::nanf("")).substeps, 0u);
  EXPECT_EQ(w->step(-1.0f).substeps, 0u);
  EXPECT_EQ(w->step(0.0f).substeps, 0u);
  // A huge frame runs the cap and reports the dropped time.
  StepReport report = w->step(10.0f);
  EXPECT_EQ(report.substeps, w->settings().maxSubstepsPerFrame);
  EXPECT_NEAR(report.droppedTime, 10.0f - report.simulatedTime, 2.0f * w->timeStep());
}

}  // namespace
}  // namespace sandphys
