// The sort of the granules by place (WorldSettings::sortInterval): it moves the granules' states
// among their slots so that slot order follows place, and changes nothing else: every body keeps
// its id and state, every contact its force and history, and a run with sorts is replayed bit for
// bit from its snapshots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>
#include <span>
#include <tuple>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

constexpr std::uint32_t kSide = 8;
constexpr std::uint32_t kLayers = 4;

// A lattice of granules falling into a box 20 d wide and 60 d high, each layer faster than the one
// below, added in a shuffled order: their slots follow no place.
void addShuffledPile(World& world) {
  const float d = world.settings().particleDiameter;
  world.addCollider(Plane{});
  world.addCollider(
      Box{.center = {0, 30 * d, 0}, .halfExtents = {10 * d, 30 * d, 10 * d}, .inside = true});
  std::vector<BodyDesc> granules;
  const float spacing = 2.4f * d;
  for (std::uint32_t j = 0; j < kLayers; ++j) {
    for (std::uint32_t k = 0; k < kSide; ++k) {
      for (std::uint32_t i = 0; i < kSide; ++i) {
        const float angle = 0.7f * float(i + 3 * j + 5 * k);
        granules.push_back({.position = {(float(i) - 3.5f) * spacing, 1.5f * d + float(j) * spacing,
                                         (float(k) - 3.5f) * spacing},
                            .orientation = fromAxisAngle(normalized(Vec3{0.3f, 1.0f, 0.2f}), angle),
                            .velocity = {0, -0.2f - 0.4f * float(j), 0}});
      }
    }
  }
  std::shuffle(granules.begin(), granules.end(), std::mt19937(7));
  world.addGranules(granules);
}

WorldSettings sortingSettings(std::uint32_t interval, float rollingFriction = 0.0f,
                              ContactLaw law = ContactLaw::HertzMindlin) {
  WorldSettings s = testing::smallSettings(2 * kSide * kSide * kLayers);
  s.sortInterval = interval;
  s.material.rollingFriction = rollingFriction;
  s.contactLaw = law;
  return s;
}

bool sameBits(const void* a, const void* b, std::size_t size) {
  return std::memcmp(a, b, size) == 0;
}

bool identical(const BodyState& a, const BodyState& b) {
  return a.id == b.id && sameBits(&a.position, &b.position, sizeof(Vec3)) &&
         sameBits(&a.orientation, &b.orientation, sizeof(Quat)) &&
         sameBits(&a.velocity, &b.velocity, sizeof(Vec3)) &&
         sameBits(&a.angularVelocity, &b.angularVelocity, sizeof(Vec3)) && a.alive == b.alive;
}

// The contacts by their bodies and place, each pair from each side (World::readContacts takes a
// pair from its lower particle's side, which a sort may change): what a sort must not change.
std::vector<ContactRecord> contactsByBody(World& world) {
  std::vector<ContactRecord> contacts = testing::contactsFromBothSides(world);
  const auto key = [](const ContactRecord& c) {
    return std::make_tuple(c.bodyA.index, c.bodyB.index, c.collider.index, c.point.x, c.point.y,
                           c.point.z);
  };
  std::sort(contacts.begin(), contacts.end(),
            [&](const ContactRecord& a, const ContactRecord& b) { return key(a) < key(b); });
  return contacts;
}

bool sameContact(const ContactRecord& a, const ContactRecord& b) {
  return a.bodyA == b.bodyA && a.bodyB == b.bodyB && a.collider == b.collider &&
         sameBits(&a.point, &b.point, sizeof(Vec3)) &&
         sameBits(&a.normal, &b.normal, sizeof(Vec3)) &&
         sameBits(&a.normalForce, &b.normalForce, sizeof(float)) &&
         sameBits(&a.tangentialForce, &b.tangentialForce, sizeof(Vec3)) &&
         sameBits(&a.tangentialDisplacement, &b.tangentialDisplacement, sizeof(Vec3)) &&
         sameBits(&a.rollingTorque, &b.rollingTorque, sizeof(Vec3)) &&
         sameBits(&a.rollingDisplacement, &b.rollingDisplacement, sizeof(Vec3));
}

// Every body (by id) and every contact the same, bit for bit.
void expectSameBodiesAndContacts(const std::vector<BodyState>& before,
                                 const std::vector<BodyState>& after,
                                 const std::vector<ContactRecord>& contactsBefore,
                                 const std::vector<ContactRecord>& contactsAfter) {
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    ASSERT_TRUE(identical(before[i], after[i])) << "body " << i;
  }
  ASSERT_EQ(contactsAfter.size(), contactsBefore.size());
  for (std::size_t i = 0; i < contactsBefore.size(); ++i) {
    ASSERT_TRUE(sameContact(contactsBefore[i], contactsAfter[i]))
        << "contact of bodies " << contactsBefore[i].bodyA.index << " and "
        << contactsBefore[i].bodyB.index;
  }
}

// Mean distance in slots between the granules of each particle contact (four particles a slot).
double meanSlotGap(const std::vector<ContactRecord>& contacts) {
  double sum = 0.0;
  std::uint32_t count = 0;
  for (const ContactRecord& c : contacts) {
    if (c.particleB == ContactRecord::kNone) continue;
    sum += std::abs(double(c.particleA / 4) - double(c.particleB / 4));
    ++count;
  }
  return count ? sum / count : 0.0;
}

struct Law {
  const char* name;
  float rollingFriction;
  ContactLaw law;
};

class GranuleOrder : public ::testing::TestWithParam<Law> {};

// Mid-fall, with contacts everywhere: the sort moves most granules to other slots, and every body
// (by id) and every contact (force, tangential and rolling springs) is the same bit for bit.
TEST_P(GranuleOrder, ASortMovesTheSlotsAndChangesNoBodyNorContact) {
  testing::TestWorld w(
      sortingSettings(kNeverSortGranules - 1, GetParam().rollingFriction, GetParam().law));
  addShuffledPile(*w);
  w->substep(1500);
  const std::vector<BodyState> before = w->readBodies();
  const std::vector<ContactRecord> contactsBefore = contactsByBody(*w);
  ASSERT_GT(contactsBefore.size(), 150u);
  testing::sortGranulesNow(*w);
  const std::vector<BodyState> after = w->readBodies();
  const std::vector<ContactRecord> contactsAfter = contactsByBody(*w);

  ASSERT_NO_FATAL_FAILURE(
      expectSameBodiesAndContacts(before, after, contactsBefore, contactsAfter));
  // The particles in slot order now belong to other bodies, and touching granules lie closer in
  // slots than in the shuffled order.
  const std::vector<ParticleState> particles = w->readParticles();
  std::uint32_t moved = 0;
  for (std::uint32_t p = 0; p < particles.size(); p += 4) moved += particles[p].body.index != p / 4;
  EXPECT_GT(moved, before.size() / 2);
  const double gapBefore = meanSlotGap(contactsBefore);
  const double gapAfter = meanSlotGap(contactsAfter);
  EXPECT_LT(gapAfter, 0.5 * gapBefore) << "mean slot gap " << gapBefore << " -> " << gapAfter;
}

INSTANTIATE_TEST_SUITE_P(Laws, GranuleOrder,
                         ::testing::Values(Law{"HertzMindlin", 0.0f, ContactLaw::HertzMindlin},
                                           Law{"RollingFriction", 0.1f, ContactLaw::HertzMindlin},
                                           Law{"PaperViscous", 0.0f, ContactLaw::PaperViscous}),
                         [](const auto& test) { return std::string(test.param.name); });

// A run that sorts every 100 substeps ends as the same bits however it gets there: restored from
// a snapshot taken at any substep into a World built alike, or read back now and then on the
// way (a read-back builds lists when they are due). So a sort's order follows from the state
// alone. When it came from whichever list build was last, a restored World put the same bodies
// in other slots (its state hash differed) after four of five of these restores.
TEST(GranuleOrderRun, EndsAsTheSameBitsWhenRestoredOrReadOnTheWay) {
  constexpr std::uint32_t kEnd = 300;  // before the next sort, which might even out an order
  testing::TestWorld original(sortingSettings(100));
  addShuffledPile(*original);
  original->substep(kEnd);
  EXPECT_EQ(original->readStats().granuleSorts, 2u);
  const std::vector<BodyState> a = original->readBodies();
  const auto expectSameEnd = [&](World& world) {
    EXPECT_EQ(world.readStateHash(), original->readStateHash());
    const std::vector<BodyState> b = world.readBodies();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(identical(a[i], b[i])) << "body " << i;
  };

  for (std::uint32_t at : {110u, 130u, 170u, 199u, 250u}) {
    SCOPED_TRACE(::testing::Message() << "restored at substep " << at);
    testing::TestWorld first(sortingSettings(100));
    addShuffledPile(*first);
    first->substep(at);
    const WorldSnapshot snapshot = first->readSnapshot();
    ASSERT_EQ(snapshot.bodyIds.size(), at > 100 ? snapshot.bodies.size() : 0u);
    EXPECT_EQ(stateHash(snapshot), first->readStateHash());
    testing::TestWorld replay(sortingSettings(100));
    addShuffledPile(*replay);
    replay->restoreSnapshot(snapshot);
    EXPECT_EQ(replay->readStateHash(), stateHash(snapshot));
    replay->substep(kEnd - at);
    expectSameEnd(*replay);
  }

  SCOPED_TRACE("read on the way");
  testing::TestWorld observed(sortingSettings(100));
  addShuffledPile(*observed);
  for (std::uint32_t done = 0; done < kEnd; done += 30) {
    observed->substep(30);
    observed->readContacts();
  }
  expectSameEnd(*observed);
}

// A body set by id after sorts is that body: its new pose reads back under its id, and so does a
// granule added after them, under the id it was given.
TEST(GranuleOrderRun, BodiesAreSetAndReadByTheirIds) {
  testing::TestWorld w(sortingSettings(50));
  addShuffledPile(*w);
  w->substep(120);
  const BodyId id{17, 0};
  const float d = w->settings().particleDiameter;
  const BodyDesc lifted{.position = {0.0f, 30 * d, 0.0f}};
  w->setBodyState(id, lifted);
  const BodyState state = w->readBody(id);
  EXPECT_EQ(state.id, id);
  EXPECT_EQ(state.position.y, lifted.position.y);
  const BodyDesc added{.position = {5 * d, 40 * d, 5 * d}};
  const std::vector<BodyId> ids = w->addGranules(std::span<const BodyDesc>(&added, 1));
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(w->readBody(ids[0]).position.y, added.position.y);
  w->substep(60);  // one more sort
  // Still the bodies up there, falling.
  EXPECT_GT(w->readBody(id).position.y, 25 * d);
  EXPECT_GT(w->readBody(ids[0]).position.y, 35 * d);
  EXPECT_LT(w->readBody(ids[0]).position.y, 40 * d);
}

// Left at 0, the interval is kSortInterval, with sleep as without (the falling pile is awake):
// the shuffled pile's granules have moved to other slots after two sorts. With
// kNeverSortGranules every slot still holds the body added in it.
TEST(GranuleOrderRun, SortsEveryThousandSubstepsByDefault) {
  struct Case {
    bool sleep;
    std::uint32_t interval;
    bool sorts;
  };
  for (const Case c :
       {Case{false, 0, true}, Case{true, 0, true}, Case{false, kNeverSortGranules, false},
        Case{true, kNeverSortGranules, false}}) {
    SCOPED_TRACE(::testing::Message() << "sleep " << c.sleep << ", interval " << c.interval);
    WorldSettings s = sortingSettings(c.interval);
    s.sleep.enabled = c.sleep;
    testing::TestWorld w(s);
    addShuffledPile(*w);
    w->substep(2 * kSortInterval + 1);  // the substeps after 1000 and 2000 sort
    const std::vector<ParticleState> particles = w->readParticles();
    std::uint32_t moved = 0;
    for (std::uint32_t p = 0; p < particles.size(); p += 4)
      moved += particles[p].body.index != p / 4;
    if (c.sorts) {
      EXPECT_GT(moved, particles.size() / 8);
      EXPECT_EQ(w->readStats().granuleSorts, 2u);
    } else {
      EXPECT_EQ(moved, 0u);
      EXPECT_EQ(w->readStats().granuleSorts, 0u);
    }
  }
}

WorldSettings sleepingSettings(std::uint32_t interval) {
  WorldSettings s = testing::smallSettings();
  s.sleep.enabled = true;
  s.sortInterval = interval;
  return s;
}

// testing::buildPile with sleep, caught half asleep: a snapshot taken without sorts.
WorldSnapshot halfAsleepPile() {
  testing::TestWorld w(sleepingSettings(kNeverSortGranules));
  testing::buildPile(*w);
  std::uint32_t asleep = 0;
  while (w->simulatedTime() < 1.5 && asleep < 30) {
    w.simulate(0.05);
    asleep = w->readStats().granulesAsleep;
  }
  return w->readSnapshot();
}

// With sleep a sort moves only the granules the substep computes, among their own slots: every
// sleeper that nothing touched keeps its slot. As without sleep, every body (by id), its calm
// count, every particle's force and every contact are the same bit for bit; only the marks of
// the sleepers that something touched are taken back, as in every substep that lists them.
TEST(GranuleOrderRun, WithSleepOnlyTheComputedGranulesTradeSlots) {
  const WorldSnapshot half = halfAsleepPile();
  testing::TestWorld w(sleepingSettings(kNeverSortGranules - 1));
  testing::buildPile(*w);
  w->restoreSnapshot(half);
  const std::uint32_t asleep = w->readStats().granulesAsleep;
  ASSERT_GT(asleep, 20u);
  ASSERT_LT(asleep, 70u);
  const std::uint32_t sleeping = w->sleepModel().substeps;
  const std::vector<BodyState> before = w->readBodies();
  const std::vector<ContactRecord> contactsBefore = contactsByBody(*w);
  testing::sortGranulesNow(*w);
  const std::vector<BodyState> after = w->readBodies();
  const std::vector<ContactRecord> contactsAfter = contactsByBody(*w);
  const WorldSnapshot sorted = w->readSnapshot();

  ASSERT_NO_FATAL_FAILURE(
      expectSameBodiesAndContacts(before, after, contactsBefore, contactsAfter));
  ASSERT_EQ(sorted.bodyIds.size(), half.bodies.size());
  std::uint32_t moved = 0;
  for (std::uint32_t slot = 0; slot < sorted.bodyIds.size(); ++slot) {
    const std::uint32_t id = sorted.bodyIds[slot];
    const StoredBody& was = half.bodies[id];
    moved += id != slot;
    if (was.calm == sleeping) {
      EXPECT_EQ(id, slot) << "a sleeper nothing touched moved";
    }
    EXPECT_EQ(sorted.bodies[slot].calm, std::min(was.calm, sleeping)) << "body " << id;
    for (std::uint32_t k = 0; k < 4; ++k) {
      EXPECT_EQ(
          std::memcmp(&sorted.forces[4 * slot + k], &half.forces[4 * id + k], sizeof(StoredForces)),
          0)
          << "body " << id << " particle " << k;
    }
  }
  EXPECT_GT(moved, (half.bodies.size() - asleep) / 2);
}

// A run with sleep that sorts every 100 substeps, from the half sleeping pile, ends as the same
// bits however it gets there: restored from a snapshot at any substep, or read on the way.
TEST(GranuleOrderRun, WithSleepEndsAsTheSameBitsWhenRestoredOrReadOnTheWay) {
  constexpr std::uint32_t kRun = 300;
  const WorldSnapshot half = halfAsleepPile();
  const auto fromHalf = [&](testing::TestWorld& w) {
    testing::buildPile(*w);
    w->restoreSnapshot(half);
  };
  testing::TestWorld original(sleepingSettings(100));
  fromHalf(original);
  original->substep(kRun);
  EXPECT_EQ(original->readStats().granuleSorts - (half.steps - 1) / 100, 3u);
  const std::uint64_t hash = original->readStateHash();
  const WorldSnapshot end = original->readSnapshot();
  std::uint32_t moved = 0;
  for (std::uint32_t slot = 0; slot < end.bodyIds.size(); ++slot)
    moved += end.bodyIds[slot] != slot;
  EXPECT_GT(moved, 10u);

  for (std::uint32_t at : {10u, 40u, 90u, 130u, 250u}) {
    SCOPED_TRACE(::testing::Message() << "restored " << at << " substeps on");
    testing::TestWorld first(sleepingSettings(100));
    fromHalf(first);
    first->substep(at);
    testing::TestWorld replay(sleepingSettings(100));
    testing::buildPile(*replay);
    replay->restoreSnapshot(first->readSnapshot());
    replay->substep(kRun - at);
    const auto difference = firstDifference(end, replay->readSnapshot());
    EXPECT_FALSE(difference.has_value()) << difference->describe();
    EXPECT_EQ(replay->readStateHash(), hash);
  }

  SCOPED_TRACE("read on the way");
  testing::TestWorld observed(sleepingSettings(100));
  fromHalf(observed);
  for (std::uint32_t done = 0; done < kRun; done += 30) {
    observed->substep(30);
    observed->readContacts();
  }
  EXPECT_EQ(observed->readStateHash(), hash);
}

// The other kinds of body beside the granules: a static rough floor, a dynamic rock of many
// particles, a kinematic bar on a move, and a sink that kills the granules that reach a corner.
struct MixedScene {
  BodyId floor, rock, bar;
};

MixedScene addMixedScene(World& world) {
  const float d = world.settings().particleDiameter;
  MixedScene scene;
  world.addCollider(Plane{});
  world.addCollider(
      Box{.center = {0, 30 * d, 0}, .halfExtents = {10 * d, 30 * d, 10 * d}, .inside = true});
  scene.floor = world.addRoughFloor(RoughFloor{.halfExtentX = 9.5f * d, .halfExtentZ = 9.5f * d});
  world.addSink(Sink{.min = {6 * d, -d, 6 * d}, .max = {10 * d, 3 * d, 10 * d}});
  std::vector<Vec3> cube;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      for (int k = -1; k <= 1; ++k) cube.push_back(Vec3{float(i), float(j), float(k)} * d);
    }
  }
  scene.rock = world.addBody(makeParticleTemplate(cube, d, 3000.0f),
                             BodyDesc{.position = {-3 * d, 10 * d, 2 * d}, .velocity = {0, -1, 0}});
  std::vector<Vec3> bar;
  for (int k = -3; k <= 3; ++k) bar.push_back(Vec3{0, 0, float(k)} * d);
  const Vec3 from{-8 * d, 2.5f * d, 0}, to{8 * d, 2.5f * d, 0};
  scene.bar = world.addBody(makeParticleTemplate(bar, d, 3000.0f),
                            BodyDesc{.position = from, .motion = Motion::Kinematic});
  world.moveKinematic(scene.bar,
                      KinematicMove{.from = from, .to = to, .startTime = 0.01, .duration = 0.06});
  world.addGranules(GranuleBlock{
      .center = {0, 6 * d, 0}, .countX = 6, .countY = 4, .countZ = 6, .velocity = {0, -0.5f, 0}});
  return scene;
}
constexpr std::uint32_t kMixedGranules = 6 * 4 * 6;

WorldSettings mixedSettings(bool sleep) {
  WorldSettings s = sortingSettings(100);
  s.maxParticles = 4096;
  s.sleep.enabled = sleep;
  return s;
}

// Beside bodies of every other kind, mid-move and with granules killed, a sort moves only the
// live granules: every body (by id) and every contact is the same bit for bit and every other
// body keeps its slot; and a run that sorts every 100 substeps ends as the same bits when
// restored or read on the way.
TEST(GranuleOrderRun, BesideBodiesOfEveryOtherKindASortMovesOnlyTheLiveGranules) {
  for (const bool sleep : {false, true}) {
    SCOPED_TRACE(sleep ? "with sleep" : "without sleep");
    constexpr std::uint32_t kSortAt = 650;  // mid-move, with granules killed
    testing::TestWorld w(mixedSettings(sleep));
    const MixedScene scene = addMixedScene(*w);
    w->substep(kSortAt);
    const WorldSnapshot was = w->readSnapshot();
    const std::uint32_t alive = w->readStats().granulesAlive;
    ASSERT_LT(alive, kMixedGranules) << "no granule reached the sink";
    const std::vector<BodyState> before = w->readBodies();
    const std::vector<ContactRecord> contactsBefore = contactsByBody(*w);
    for (const BodyId body : {scene.floor, scene.rock, scene.bar}) {
      ASSERT_TRUE(
          std::any_of(contactsBefore.begin(), contactsBefore.end(),
                      [&](const ContactRecord& c) { return c.bodyA == body || c.bodyB == body; }))
          << "body " << body.index << " touches no granule";
    }
    testing::sortGranulesNow(*w);
    const std::vector<ContactRecord> contactsAfter = contactsByBody(*w);
    ASSERT_NO_FATAL_FAILURE(
        expectSameBodiesAndContacts(before, w->readBodies(), contactsBefore, contactsAfter));
    const WorldSnapshot sorted = w->readSnapshot();
    ASSERT_EQ(sorted.bodyIds.size(), was.bodies.size());
    std::uint32_t moved = 0;
    for (std::uint32_t slot = 0; slot < sorted.bodyIds.size(); ++slot) {
      const std::uint32_t id = sorted.bodyIds[slot];
      moved += id != slot;
      if (!was.bodies[slot].alive || slot == scene.floor.index || slot == scene.rock.index ||
          slot == scene.bar.index) {
        EXPECT_EQ(id, slot) << "a body that is not a live granule moved";
      }
    }
    EXPECT_GT(moved, alive / 2);

    constexpr std::uint32_t kEnd = 1500;
    testing::TestWorld original(mixedSettings(sleep));
    addMixedScene(*original);
    original->substep(kEnd);
    EXPECT_EQ(original->readStats().granuleSorts, (kEnd - 1) / 100);  // at 101, 201, ...
    for (const std::uint32_t at : {450u, 1234u}) {
      SCOPED_TRACE(::testing::Message() << "restored at substep " << at);
      testing::TestWorld first(mixedSettings(sleep));
      addMixedScene(*first);
      first->substep(at);
      testing::TestWorld replay(mixedSettings(sleep));
      addMixedScene(*replay);
      replay->restoreSnapshot(first->readSnapshot());
      replay->substep(kEnd - at);
      EXPECT_EQ(replay->readStateHash(), original->readStateHash());
    }
    testing::TestWorld observed(mixedSettings(sleep));
    addMixedScene(*observed);
    for (std::uint32_t done = 0; done < kEnd; done += 75) {
      observed->substep(75);
      observed->readContacts();
    }
    EXPECT_EQ(observed->readStateHash(), original->readStateHash()) << "read on the way";
  }
}

// A World grown (World::reserve) after sorts keeps every body's id in its slot: set by id and run
// on, it ends as the same bits as one that was not grown.
TEST(GranuleOrderRun, AWorldGrownAfterSortsGoesOnAsOneThatWasNot) {
  for (const bool sleep : {false, true}) {
    SCOPED_TRACE(sleep ? "with sleep" : "without sleep");
    WorldSettings settings = sortingSettings(100);
    settings.sleep.enabled = sleep;
    testing::TestWorld kept(settings), grown(settings);
    for (World* world : {&*kept, &*grown}) {
      addShuffledPile(*world);
      world->substep(250);
      ASSERT_EQ(world->readStats().granuleSorts, 2u);
    }
    grown->reserve(4 * grown->bodyCapacity(), 4 * grown->particleCapacity());
    // The top layer's first granule, lifted by two diameters.
    const BodyState top = kept->readBodies().back();
    const float d = settings.particleDiameter;
    for (World* world : {&*kept, &*grown}) {
      world->setBodyState(top.id, BodyDesc{.position = top.position + Vec3{0, 2 * d, 0},
                                           .orientation = top.orientation});
      world->substep(250);
    }
    EXPECT_EQ(grown->readStateHash(), kept->readStateHash());
    const std::vector<BodyState> a = kept->readBodies(), b = grown->readBodies();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(identical(a[i], b[i])) << "body " << i;
  }
}

}  // namespace
}  // namespace sandphys
