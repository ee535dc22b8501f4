// Kinematic moves (World::moveKinematic) and steps that stop at a substep (World::step(frameDt,
// stopAt)): a wall pushes a granule along a floor, driven by frames of 1/60 s, by one frame and by
// single substeps; the wall's path, its landing on the target and the pushed granule must be the
// same bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::errorMessageOf;
using testing::TestWorld;

constexpr double kStart = 0.05;    // s: the granule lands on the floor meanwhile
constexpr double kDuration = 0.1;  // s
constexpr float kTravel = 0.05f;   // m (2.5 d at 0.5 m/s)
constexpr double kAfter = 0.02;    // s run after the move ends

WorldSettings settings() {
  WorldSettings s = testing::smallSettings(8);
  // One frame must be able to run the whole scene.
  s.maxSubstepsPerFrame = 1u << 20;
  return s;
}

// A wall of 3 x 3 particles in the yz plane, hovering a quarter diameter above the floor.
ParticleTemplate wallShape(float d, float density) {
  std::vector<Vec3> centres;
  for (int y = -1; y <= 1; ++y) {
    for (int z = -1; z <= 1; ++z) centres.push_back({0.0f, float(y) * d, float(z) * d});
  }
  return makeParticleTemplate(centres, d, density);
}

struct Scene {
  std::unique_ptr<TestWorld> world;
  BodyId wall;
  BodyId granule;
  KinematicMove move;
  KinematicMovePlan plan;
};

Scene build() {
  Scene s;
  s.world = std::make_unique<TestWorld>(settings());
  TestWorld& w = *s.world;
  const float d = w->settings().particleDiameter;
  w.addFloor();
  const Vec3 from{0.0f, 1.75f * d, 0.0f};
  s.wall = w->addBody(wallShape(d, w->settings().material.density),
                      BodyDesc{.position = from, .motion = Motion::Kinematic});
  s.granule = w.addGranule({2.5f * d, 1.2f * d, 0.0f});
  s.move = KinematicMove{.from = from,
                         .to = {from.x + kTravel, from.y, from.z},
                         .startTime = kStart,
                         .duration = kDuration};
  s.plan = w->moveKinematic(s.wall, s.move);
  return s;
}

std::uint64_t totalSteps(const Scene& s) {
  return s.plan.endStep + std::uint64_t(std::ceil(kAfter / (**s.world).timeStep()));
}

// The exact path's nearest float at step count `step`, as KinematicMove defines it.
float pathX(const Scene& s, std::uint64_t step) {
  const double done = double(step - s.plan.startStep) / double(s.plan.endStep - s.plan.startStep);
  return float(double(s.move.from.x) + (double(s.move.to.x) - double(s.move.from.x)) * done);
}

TEST(KinematicMove, PlanFollowsTheStatedRule) {
  const Scene s = build();
  World& w = **s.world;
  const double dt = w.timeStep();
  EXPECT_EQ(s.plan.startStep, std::uint64_t(std::ceil(kStart / dt)));
  EXPECT_EQ(s.plan.endStep - s.plan.startStep, std::uint64_t(std::llround(kDuration / dt)));
  const double seconds = double(s.plan.endStep - s.plan.startStep) * dt;
  EXPECT_EQ(s.plan.velocity.x, float(double(kTravel) / seconds));
  EXPECT_EQ(s.plan.velocity.y, 0.0f);
  EXPECT_EQ(s.plan.velocity.z, 0.0f);
}

// Frames of 1/60 s, one frame for the whole run and a loop of substep(1) put the wall at the same
// place at every step count checked, land it on `to` bit for bit at the end substep, stop it
// there, and leave the granule it pushed in the same state, bit for bit.
TEST(KinematicMove, PathLandingAndPushedGranuleDoNotDependOnTheFrames) {
  std::vector<WorldSnapshot> ends;
  for (const char* driver : {"frames of 1/60 s", "one frame", "single substeps"}) {
    SCOPED_TRACE(driver);
    Scene s = build();
    World& w = **s.world;
    const std::uint64_t total = totalSteps(s);
    const std::uint64_t middle = (s.plan.startStep + s.plan.endStep) / 2;
    // Each driver stops at these counts to look (stopAt), and goes on.
    const std::uint64_t looks[] = {s.plan.startStep, middle, s.plan.endStep, total};
    for (std::uint64_t look : looks) {
      const std::string driverName = driver;
      if (driverName == "frames of 1/60 s") {
        while (w.stepCount() < look) w.step(1.0f / 60.0f, look);
      } else if (driverName == "one frame") {
        // The whole run is due at the first look; later looks run what it held.
        const float frameDt =
            w.stepCount() == 0 ? float((double(total) + 0.5) * w.timeStep()) : 0.0f;
        const StepReport report = w.step(frameDt, look);
        EXPECT_EQ(report.substepsHeld > 0, look < total);
      } else {
        while (w.stepCount() < look) w.substep(1);
      }
      ASSERT_EQ(w.stepCount(), look);
      const BodyState wall = w.readBody(s.wall);
      SCOPED_TRACE("step " + std::to_string(look));
      if (look == s.plan.startStep) {
        EXPECT_EQ(wall.position.x, s.move.from.x);
        EXPECT_EQ(wall.velocity.x, s.plan.velocity.x);
      } else if (look == middle) {
        EXPECT_EQ(wall.position.x, pathX(s, middle));
        EXPECT_EQ(wall.velocity.x, s.plan.velocity.x);
      } else {
        // Landed on `to` bit for bit, and at rest from then on.
        EXPECT_EQ(wall.position.x, s.move.to.x);
        EXPECT_EQ(wall.position.y, s.move.to.y);
        EXPECT_EQ(wall.position.z, s.move.to.z);
        EXPECT_EQ(wall.velocity.x, 0.0f);
      }
    }
    // The granule, which started where the wall ends, was pushed ahead of the wall's face: a
    // granule touching it has its centre at least 0.39 d beyond the wall's.
    const BodyState granule = w.readBody(s.granule);
    EXPECT_GT(granule.position.x, s.move.to.x + 0.3f * w.settings().particleDiameter);
    ends.push_back(w.readSnapshot());
  }
  for (std::size_t i = 1; i < ends.size(); ++i) {
    const std::optional<StateDifference> d = firstDifference(ends[0], ends[i]);
    EXPECT_FALSE(d) << "driver " << i << ": " << d->describe();
  }
}

// A World put back to a snapshot taken mid-move goes on as it did: the move is the World's, its
// pose a function of the step count.
TEST(KinematicMove, ARestoreMidMoveContinuesBitForBit) {
  Scene s = build();
  World& w = **s.world;
  const float frameDt = 1.0f / 60.0f;
  while (w.stepCount() < (s.plan.startStep + s.plan.endStep) / 2) w.step(frameDt);
  const WorldSnapshot middle = w.readSnapshot();
  const std::uint64_t total = totalSteps(s);
  std::vector<std::uint64_t> steps;
  while (w.stepCount() < total) {
    w.step(frameDt);
    steps.push_back(w.stepCount());
  }
  const WorldSnapshot later = w.readSnapshot();
  w.restoreSnapshot(middle);
  for (std::uint64_t expected : steps) {
    w.step(frameDt);
    ASSERT_EQ(w.stepCount(), expected);
  }
  const std::optional<StateDifference> d = firstDifference(later, w.readSnapshot());
  EXPECT_FALSE(d) << d->describe();
  EXPECT_EQ(w.readBody(s.wall).position.x, s.move.to.x);
}

// A step that stops holds the rest of its frame, and the next call runs it: the frames add up
// to the substeps of frames that did not stop, and a snapshot keeps what is held.
TEST(KinematicMove, AStepThatStopsHoldsTheRestOfItsFrame) {
  TestWorld plain(settings());
  TestWorld split(settings());
  for (TestWorld* w : {&plain, &split}) {
    w->addFloor();
    w->addGranule({0.0f, 0.03f, 0.0f});
  }
  const float frameDt = 1.0f / 60.0f;
  const StepReport first = plain->step(frameDt);
  plain->step(frameDt);
  const std::uint64_t stopAt = first.substeps + 5;  // inside the second frame
  ASSERT_GT(plain->stepCount(), stopAt);
  split->step(frameDt, stopAt);
  const StepReport stopped = split->step(frameDt, stopAt);
  EXPECT_EQ(split->stepCount(), stopAt);
  EXPECT_EQ(stopped.substepsHeld, plain->stepCount() - stopAt);
  const WorldSnapshot held = split->readSnapshot();
  EXPECT_EQ(held.heldSubsteps, stopped.substepsHeld);
  StepReport frame = stopped;
  frame.append(split->step(0.0f, std::numeric_limits<std::uint64_t>::max()));
  EXPECT_EQ(split->stepCount(), plain->stepCount());
  EXPECT_EQ(frame.substeps, plain->stepCount() - first.substeps);
  EXPECT_EQ(frame.substepsHeld, 0u);
  // Nothing is held now: a zero frame runs nothing.
  EXPECT_EQ(split->step(0.0f).substeps, 0u);
  split->restoreSnapshot(held);
  EXPECT_EQ(split->step(0.0f).substeps, held.heldSubsteps);
  // A stop at or before the step count runs nothing and holds the frame.
  const StepReport none = split->step(frameDt, split->stepCount());
  EXPECT_EQ(none.substeps, 0u);
  EXPECT_GT(none.substepsHeld, 0u);
}

TEST(KinematicMove, BadMovesNameTheirFieldAndValue) {
  Scene s = build();
  World& w = **s.world;
  const KinematicMove good = s.move;
  auto message = [&](BodyId id, const KinematicMove& move) {
    return errorMessageOf([&] { (void)w.moveKinematic(id, move); });
  };
  EXPECT_NE(message(BodyId{}, good).find("is invalid or stale"), std::string::npos);
  EXPECT_NE(message(BodyId{40, 0}, good).find("BodyId {index 40"), std::string::npos);
  const std::string dynamic = message(s.granule, good);
  EXPECT_NE(dynamic.find("body " + std::to_string(s.granule.index) + " has motion 0"),
            std::string::npos)
      << dynamic;
  struct Case {
    void (*edit)(KinematicMove&);
    const char* expected;
  };
  const Case cases[] = {
      {[](KinematicMove& m) { m.duration = -1.0; }, "KinematicMove.duration = -1"},
      {[](KinematicMove& m) { m.duration = std::nan(""); }, "KinematicMove.duration = nan"},
      {[](KinematicMove& m) { m.startTime = std::nan(""); }, "KinematicMove.startTime = nan"},
      {[](KinematicMove& m) { m.to.y = std::numeric_limits<float>::infinity(); },
       "KinematicMove.to"},
      {[](KinematicMove& m) {
         m.orientation = {0, 0, 0, 0};
       },
       "KinematicMove.orientation"},
  };
  for (const Case& c : cases) {
    KinematicMove bad = good;
    c.edit(bad);
    const std::string text = message(s.wall, bad);
    EXPECT_NE(text.find(c.expected), std::string::npos) << text;
  }
  // A start in the past: the World has run 0.03 s.
  w.step(0.03f);
  KinematicMove past = good;
  past.startTime = 0.01;
  const std::string text = message(s.wall, past);
  EXPECT_NE(text.find("KinematicMove.startTime = 0.01"), std::string::npos) << text;
  EXPECT_NE(text.find("in the past"), std::string::npos) << text;
  // The refused moves changed nothing: the first still runs to its end.
  while (w.stepCount() < s.plan.endStep) w.step(1.0f / 60.0f, s.plan.endStep);
  EXPECT_EQ(w.readBody(s.wall).position.x, s.move.to.x);
}

}  // namespace
}  // namespace sandphys
