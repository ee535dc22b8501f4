// StoredBody::principalOrientation is the orientation of a body's principal frame as the GPU
// stores it, BodyState::orientation · ParticleTemplate::principalRotation; a snapshot puts it back
// bit for bit, and the CPU's state hash takes it as the GPU's does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "support/test_world.h"

namespace sandphys {
namespace {

// A slanted rod of three particles, spinning in free flight: its principal frame is not its
// template's, and its orientation changes every substep.
BodyId addSpinningRod(testing::TestWorld& w, ParticleTemplate& rod) {
  const float d = w->settings().particleDiameter;
  rod = makeParticleTemplate({{0, 0, 0}, {d, d, 0}, {2 * d, 2 * d, 0}}, d,
                             w->settings().material.density);
  return w->addBody(rod, {.position = {0, 1, 0},
                          .orientation = fromAxisAngle(normalized({1, 2, 3}), 0.7f),
                          .angularVelocity = {1.0f, -2.0f, 3.0f}});
}

TEST(SnapshotOrientation, IsTheReadBackOrientationInThePrincipalFrame) {
  testing::TestWorld w;
  ParticleTemplate rod;
  const BodyId id = addSpinningRod(w, rod);
  ASSERT_LT(std::abs(rod.principalRotation.w), 0.999f) << "the rod's frames coincide";
  w.simulate(0.01);
  const Quat read = w->readBody(id).orientation;
  const Quat stored = w->readSnapshot().bodies[id.index].principalOrientation;
  // readBody takes the principal rotation out in float; putting it back agrees to rounding.
  const Quat expected = read * rod.principalRotation;
  EXPECT_NEAR(stored.w, expected.w, 1e-6f);
  EXPECT_NEAR(stored.x, expected.x, 1e-6f);
  EXPECT_NEAR(stored.y, expected.y, 1e-6f);
  EXPECT_NEAR(stored.z, expected.z, 1e-6f);
}

TEST(SnapshotOrientation, IsRestoredBitForBitAndHashedAsTheGpuHashesIt) {
  testing::TestWorld w;
  ParticleTemplate rod;
  const BodyId id = addSpinningRod(w, rod);
  w.simulate(0.01);
  const WorldSnapshot taken = w->readSnapshot();
  const std::uint64_t hash = w->readStateHash();
  EXPECT_EQ(stateHash(taken), hash);
  w.simulate(0.01);
  const Quat moved = w->readSnapshot().bodies[id.index].principalOrientation;
  EXPECT_NE(std::memcmp(&moved, &taken.bodies[id.index].principalOrientation, sizeof moved), 0);
  w->restoreSnapshot(taken);
  const WorldSnapshot restored = w->readSnapshot();
  const Quat& back = restored.bodies[id.index].principalOrientation;
  EXPECT_EQ(std::memcmp(&back, &taken.bodies[id.index].principalOrientation, sizeof back), 0);
  EXPECT_FALSE(firstDifference(taken, restored)) << firstDifference(taken, restored)->describe();
  EXPECT_EQ(w->readStateHash(), hash);
}

}  // namespace
}  // namespace sandphys
