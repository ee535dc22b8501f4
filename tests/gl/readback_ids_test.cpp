// Read-backs name bodies and colliders by the typed ids the World handed out: BodyState::id,
// ParticleState::body and a ContactRecord's bodies and collider are the ids addGranules, addBody
// and addCollider returned, and every call that takes an id accepts them. A BodyRange hands out
// its ids without anyone building one.
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(ReadbackIds, AreTheIdsTheBodiesWereAddedWith) {
  testing::TestWorld w;
  const float d = w->settings().particleDiameter;
  const ColliderId floor = w.addFloor();
  const BodyRange block = w->addGranules(
      GranuleBlock{.center = {-0.5f, 0.3f, 0.0f}, .countX = 2, .countY = 1, .countZ = 3});
  // Two spheres that touch each other; the first also sinks a little into the floor.
  const BodyId low = w.addSphere({0.0f, 0.45f * d, 0.0f});
  const BodyId high = w.addSphere({0.95f * d, 0.6f * d, 0.0f});

  const std::vector<BodyState> bodies = w->readBodies();
  ASSERT_EQ(bodies.size(), block.size() + 2);
  std::uint32_t i = 0;
  for (const BodyId id : block) {
    EXPECT_EQ(block[i++], id);
    EXPECT_TRUE(block.contains(id));
    // readBodies holds one state per slot, in slot order.
    const BodyState& s = bodies[id.index];
    EXPECT_EQ(s.id, id);
    EXPECT_TRUE(s.granule);
    // A read-back's id works wherever an id does.
    EXPECT_EQ(w->readBody(s.id).position, s.position);
  }
  EXPECT_EQ(i, 6u);
  EXPECT_EQ(bodies[low.index].id, low);
  EXPECT_EQ(bodies[high.index].id, high);
  EXPECT_FALSE(block.contains(low));
  EXPECT_FALSE(block.contains(BodyId{}));
  EXPECT_FALSE(block.contains(BodyId{block[0].index, block[0].generation + 1}));  // stale
  EXPECT_THROW((void)block[block.size()], InvalidArgument);
  w->setBodyState(bodies[high.index].id, BodyDesc{.position = {0.95f * d, 0.6f * d, 0.0f}});

  std::map<std::uint32_t, std::uint32_t> particlesOf;  // by slot
  for (const ParticleState& p : w->readParticles()) {
    ASSERT_EQ(bodies.at(p.body.index).id, p.body);
    ++particlesOf[p.body.index];
  }
  EXPECT_EQ(particlesOf[block[0].index], 4u);
  EXPECT_EQ(particlesOf[low.index], 1u);
  EXPECT_EQ(particlesOf[high.index], 1u);

  const std::vector<ContactRecord> contacts = w->readContacts();
  ASSERT_EQ(contacts.size(), 2u);
  const ContactRecord* onFloor = nullptr;
  const ContactRecord* between = nullptr;
  for (const ContactRecord& c : contacts) (c.collider.isValid() ? onFloor : between) = &c;
  ASSERT_TRUE(onFloor && between);
  EXPECT_EQ(onFloor->bodyA, low);
  EXPECT_FALSE(onFloor->bodyB.isValid());
  EXPECT_EQ(onFloor->collider, floor);
  EXPECT_EQ(onFloor->particleB, ContactRecord::kNone);
  EXPECT_EQ(between->bodyA, low);
  EXPECT_EQ(between->bodyB, high);
  EXPECT_FALSE(between->collider.isValid());
  EXPECT_EQ(w->readBody(between->bodyB).position, bodies[high.index].position);
}

// Bodies placed before any step (or between steps) show in readParticles where the next substep
// starts them, and so do their motion and the floor's: Static, Kinematic, Dynamic in BodyState.
TEST(ReadbackIds, ParticlesOfBodiesJustPlacedAreWhereTheirBodiesAre) {
  testing::TestWorld w;
  const float d = w->settings().particleDiameter;
  const BodyId floor = w->addRoughFloor(RoughFloor{.center = {0.0f, -0.1f, 0.0f}, .radius = 3 * d});
  const BodyId sphere = w.addSphere({0.25f, 0.5f, -0.125f});
  const BodyId carried = w->addBody(makeParticleTemplate({{0.0f, 0.0f, 0.0f}}, d, 2600.0f),
                                    {.position = {0.5f, 0.25f, 0.0f}, .motion = Motion::Kinematic});
  for (const ParticleState& p : w->readParticles()) {
    if (p.body == sphere) {
      EXPECT_EQ(p.position, (Vec3{0.25f, 0.5f, -0.125f}));
    } else if (p.body == carried) {
      EXPECT_EQ(p.position, (Vec3{0.5f, 0.25f, 0.0f}));
    } else if (p.body == floor) {
      EXPECT_FLOAT_EQ(p.position.y, -0.1f);
    }
  }
  const std::vector<BodyState> bodies = w->readBodies();
  EXPECT_EQ(bodies[floor.index].motion, Motion::Static);
  EXPECT_EQ(bodies[sphere.index].motion, Motion::Dynamic);
  EXPECT_EQ(bodies[carried.index].motion, Motion::Kinematic);
  // Moved by the CPU between steps: read where it was put.
  w->setBodyState(carried, {.position = {0.5f, 0.3f, 0.0f}, .motion = Motion::Kinematic});
  for (const ParticleState& p : w->readParticles()) {
    if (p.body == carried) {
      EXPECT_EQ(p.position, (Vec3{0.5f, 0.3f, 0.0f}));
    }
  }
}

}  // namespace
}  // namespace sandphys
