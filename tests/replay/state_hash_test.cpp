// The state hash of a recording: the GPU reduction equals its CPU twin (sandphys::stateHash) on the
// bits of World::readSnapshot, in every body slot, and one flipped bit of one body changes it.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

void addPile(World& world, std::uint32_t countX, std::uint32_t countY, std::uint32_t countZ) {
  world.addCollider(Plane{});
  world.addGranules(GranuleBlock{.center = {0, 0.25f, 0},
                                 .countX = countX,
                                 .countY = countY,
                                 .countZ = countZ,
                                 .velocity = {0.1f, -1.0f, 0.0f},
                                 .seed = 5});
}

TEST(StateHash, TheGpuHashIsItsCpuTwinAndFollowsOneBitOfOneBody) {
  testing::TestWorld w;
  addPile(*w, 4, 3, 4);
  w->substep(200);
  const WorldSnapshot before = w->readSnapshot();
  ASSERT_EQ(before.bodies.size(), 48u);
  const std::uint64_t hash = w->readStateHash();
  EXPECT_EQ(hash, stateHash(before));
  EXPECT_EQ(w->readStateHash(), hash) << "reading the hash changed the state";

  testing::flipVelocityBit(*w, 17, 1);
  const WorldSnapshot after = w->readSnapshot();
  const std::uint64_t changed = w->readStateHash();
  EXPECT_NE(changed, hash);
  EXPECT_EQ(changed, stateHash(after));
  const std::optional<StateDifference> difference = firstDifference(before, after);
  ASSERT_TRUE(difference);
  EXPECT_EQ(difference->body, 17u);
  EXPECT_EQ(difference->field, "velocity.y");
  EXPECT_EQ(std::bit_cast<std::uint32_t>(float(difference->recorded)) ^
                std::bit_cast<std::uint32_t>(float(difference->replayed)),
            1u);

  // Moving on changes it again, and the twin still agrees.
  w->substep(10);
  EXPECT_NE(w->readStateHash(), changed);
  EXPECT_EQ(w->readStateHash(), stateHash(w->readSnapshot()));
}

TEST(StateHash, CoversBodiesBeyondOneStrideOfTheReduction) {
  // 32 workgroups of 256 threads cover 8192 slots a pass; 9000 granules need a second.
  testing::TestWorld w(testing::smallSettings(9000));
  addPile(*w, 30, 10, 30);
  const std::uint64_t hash = w->readStateHash();
  EXPECT_EQ(hash, stateHash(w->readSnapshot()));
  testing::flipVelocityBit(*w, 8999, 2);
  EXPECT_NE(w->readStateHash(), hash);
  EXPECT_EQ(w->readStateHash(), stateHash(w->readSnapshot()));
}

// A World put back to a snapshot continues exactly as it did from there: body states are all the
// state a substep starts from (particles, grid and contacts are rebuilt from them every substep),
// and the frame time not yet stepped comes back with them. Frames of about 37.5 substeps leave
// part of a substep over for the next frame.
TEST(Snapshot, ARestoredWorldContinuesAsItDidBitForBit) {
  testing::TestWorld w;
  addPile(*w, 4, 3, 4);
  const float frameDt = static_cast<float>(37.5 * static_cast<double>(w->timeStep()));
  for (int frame = 0; frame < 5; ++frame) w->step(frameDt);
  const WorldSnapshot then = w->readSnapshot();
  ASSERT_GT(then.unsteppedTime, 0.0);
  std::vector<std::uint64_t> steps;
  for (int frame = 0; frame < 3; ++frame) {
    w->step(frameDt);
    steps.push_back(w->stepCount());
  }
  const WorldSnapshot later = w->readSnapshot();
  ASSERT_TRUE(firstDifference(then, later));

  w->restoreSnapshot(then);
  EXPECT_FALSE(firstDifference(then, w->readSnapshot()));
  EXPECT_EQ(w->stepCount(), then.steps);
  EXPECT_EQ(w->simulatedTime(), then.simulatedTime);
  EXPECT_EQ(w->readStateHash(), stateHash(then));
  // A bare World's state does not depend on how substeps fall into frames, a scene's does: each
  // frame must run the substeps it ran.
  for (int frame = 0; frame < 3; ++frame) {
    w->step(frameDt);
    EXPECT_EQ(w->stepCount(), steps[frame]) << "frame " << frame;
  }
  const std::optional<StateDifference> difference = firstDifference(later, w->readSnapshot());
  EXPECT_FALSE(difference) << difference->describe();
}

// With rolling friction each contact slot keeps a rolling spring: the snapshot carries it, the
// GPU hash and its CPU twin absorb it, a restore puts it back, and a restore without it (the
// springs zeroed, all else the same) runs differently, so it is state.
TEST(Snapshot, RollingSpringsAreStateThatTheSnapshotAndTheHashCarry) {
  WorldSettings settings = testing::smallSettings(96);
  settings.material.rollingFriction = 0.1f;
  testing::TestWorld w(settings);
  testing::buildPile(*w);
  w->substep(1500);
  const WorldSnapshot then = w->readSnapshot();
  ASSERT_EQ(then.rolling.size(), then.contacts.size());
  std::size_t loaded = 0;
  for (const StoredRolling& r : then.rolling) {
    for (const auto& spring : r.springs) loaded += spring != decltype(spring){};
  }
  std::size_t inUse = 0;
  for (const StoredContacts& c : then.contacts) inUse += std::min(c.pairs[3], kContactSlots);
  EXPECT_GT(loaded, 20u) << "too few rolling springs in use to test (" << inUse << " slots)";
  EXPECT_EQ(w->readStateHash(), stateHash(then));
  w->substep(50);
  const WorldSnapshot later = w->readSnapshot();

  w->restoreSnapshot(then);
  EXPECT_EQ(w->readStateHash(), stateHash(then));
  // Where 50 substeps from a snapshot (on a grown World) first differ from `later`.
  auto differenceAfter = [&](const WorldSnapshot& from, bool grow) {
    w->restoreSnapshot(from);
    if (grow) w->reserve(200, 800);
    w->substep(50);
    return firstDifference(later, w->readSnapshot());
  };
  const std::optional<StateDifference> same = differenceAfter(then, false);
  EXPECT_FALSE(same) << same->describe();
  // Grown, the World keeps them (the buffer and the image its kernel writes through move).
  const std::optional<StateDifference> grown = differenceAfter(then, true);
  EXPECT_FALSE(grown) << grown->describe();

  WorldSnapshot unrolled = then;
  for (StoredRolling& r : unrolled.rolling) r = StoredRolling{};
  EXPECT_NE(stateHash(unrolled), stateHash(then));
  const std::optional<StateDifference> named = firstDifference(then, unrolled);
  ASSERT_TRUE(named);
  EXPECT_NE(named->field.find("rolling"), std::string::npos) << named->field;
  EXPECT_TRUE(differenceAfter(unrolled, false))
      << "the rolling springs left no trace in 50 substeps";

  WorldSnapshot missing = then;
  missing.rolling.clear();
  try {
    w->restoreSnapshot(missing);
    FAIL() << "a snapshot without its rolling springs was restored";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("WorldSnapshot.rolling.size()"), std::string::npos)
        << error.what();
  }
}

TEST(Snapshot, SlotsAddedAfterItAreHiddenAndALargerOneIsRefused) {
  testing::TestWorld w;
  addPile(*w, 2, 2, 2);
  w->substep(20);
  const WorldSnapshot eight = w->readSnapshot();
  ASSERT_EQ(eight.bodies.size(), 8u);
  w->addGranules(GranuleBlock{.center = {0, 0.6f, 0}, .countX = 2, .countY = 2, .countZ = 2});
  w->substep(20);
  w->restoreSnapshot(eight);
  const WorldSnapshot restored = w->readSnapshot();
  ASSERT_EQ(restored.bodies.size(), 16u);
  for (std::size_t i = 8; i < 16; ++i) EXPECT_FALSE(restored.bodies[i].alive) << i;
  EXPECT_EQ(w->readStats().granulesAlive, 8u);

  WorldSnapshot tooMany = restored;
  tooMany.bodies.resize(20);
  try {
    w->restoreSnapshot(tooMany);
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("WorldSnapshot.bodies.size() = 20"), std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(firstDifference(restored, w->readSnapshot()))
      << "a refused restore changed the World";
}

}  // namespace
}  // namespace sandphys
