// Sleeping sand (WorldSettings::sleep, docs/architecture.md "sleep"): a settled pile falls
// asleep within the stated time and then changes no bit while nothing touches it; it wakes
// where it is touched or asked to; the sleep state is part of the state snapshots and the hash
// carry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::buildPile;
using testing::sleepingPileSettings;
// buildPile's granules.
constexpr std::uint32_t kGranules = 96;

// Simulates in steps of `chunk` seconds until every granule sleeps or `limit` seconds have run;
// returns the simulated time at which they all slept (or a negative value).
double sleepAll(testing::TestWorld& w, double limit, double chunk = 0.05) {
  for (double t = 0.0; t < limit; t += chunk) {
    w.simulate(chunk);
    if (w->readStats().granulesAsleep == kGranules) return w->simulatedTime();
  }
  return -1.0;
}

// The default settings with sleep.
WorldSettings withSleep() {
  WorldSettings s = testing::smallSettings();
  s.sleep.enabled = true;
  return s;
}

TEST(Sleep, DefaultsFollowFromDiameterAndGravity) {
  testing::TestWorld w(withSleep());
  const SleepModel& m = w->sleepModel();
  const double d = w->settings().particleDiameter;
  const double g = 9.81;
  EXPECT_TRUE(m.enabled);
  EXPECT_NEAR(m.linearSpeed, kSleepLinearSpeed * std::sqrt(g * d), 1e-6);
  EXPECT_NEAR(m.angularSpeed, kSleepAngularSpeed * std::sqrt(g / d), 1e-5);
  EXPECT_NEAR(m.time, kSleepTime * std::sqrt(d / g), 1e-6);
  EXPECT_NEAR(m.wakeAcceleration, kSleepWakeAcceleration * g, 1e-5);
  EXPECT_EQ(m.substeps, std::uint32_t(std::ceil(double(m.time) / w->timeStep())));
}

TEST(Sleep, BadSettingsAreRefusedByName) {
  auto refused = [](WorldSettings s, const char* field) {
    try {
      World w(testing::gpu(), s);
    } catch (const InvalidArgument& e) {
      return std::string(e.what()).find(field) != std::string::npos;
    }
    return false;
  };
  WorldSettings s = withSleep();
  s.sleep.linearSpeed = std::nanf("");
  EXPECT_TRUE(refused(s, "WorldSettings.sleep.linearSpeed"));
  s = withSleep();
  s.sleep.time = -1.0f;
  EXPECT_TRUE(refused(s, "WorldSettings.sleep.time"));
  s = withSleep();
  s.contactLaw = ContactLaw::PaperViscous;
  EXPECT_TRUE(refused(s, "WorldSettings.contactLaw"));
  s = withSleep();
  s.gravity = {};
  EXPECT_TRUE(refused(s, "gravity"));
}

TEST(Sleep, SettledPileFallsAsleepAndThenChangesNoBit) {
  testing::TestWorld w(sleepingPileSettings());
  buildPile(*w);
  // Settling takes well under 0.6 s here; asleep within the sleep time after that.
  const double limit = 0.6 + w->sleepModel().time + 0.2;
  const double asleep = sleepAll(w, limit);
  std::printf("all %u granules asleep at %.3f s (sleep time %.3f s)\n", kGranules, asleep,
              double(w->sleepModel().time));
  ASSERT_GT(asleep, 0.0) << "not all granules asleep within " << limit << " s";
  EXPECT_GT(w->readStats().contacts, 30u);  // a pile, resting on its contacts
  const WorldSnapshot before = w->readSnapshot();
  for (const StoredBody& b : before.bodies) {
    if (b.calm == 0) continue;  // colliders' bodies, if any
    EXPECT_EQ(b.calm, w->sleepModel().substeps);
  }
  const std::uint64_t hash = w->readStateHash();
  w.simulate(0.3);
  EXPECT_EQ(w->readStateHash(), hash);
  EXPECT_FALSE(firstDifference(before, w->readSnapshot()).has_value());
  EXPECT_EQ(w->readStats().granulesAsleep, kGranules);
}

TEST(Sleep, WakeWakesTheRegionAndThePileSleepsAgainWhereItWas) {
  testing::TestWorld w(sleepingPileSettings());
  buildPile(*w);
  ASSERT_GT(sleepAll(w, 2.0), 0.0);
  const std::vector<BodyState> slept = w->readBodies();
  // The lower half of the box.
  w->wake({-1, -1, -1}, {1, 0.04f, 1});
  const std::uint32_t asleep = w->readStats().granulesAsleep;
  EXPECT_LT(asleep, kGranules);
  EXPECT_GT(asleep, 0u);
  w->wake({-1, -1, -1}, {1, 1, 1});
  EXPECT_EQ(w->readStats().granulesAsleep, 0u);
  // Nothing unbalanced them: they fall asleep again after the sleep time, having moved far less
  // than a hundredth of a diameter.
  const double woken = w->simulatedTime();
  const double again = sleepAll(w, 2.0 * w->sleepModel().time, 0.02) - woken;
  ASSERT_GT(again, 0.0);
  const std::vector<BodyState> after = w->readBodies();
  const double d = w->settings().particleDiameter;
  double worst = 0.0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const Vec3 a = after[i].position, b = slept[i].position;
    worst = std::max(worst, double(std::hypot(a.x - b.x, a.y - b.y, a.z - b.z)));
  }
  std::printf("woken pile asleep again after %.3f s, moved at most %.2e d\n", again, worst / d);
  EXPECT_LT(worst, 0.01 * d);
}

TEST(Sleep, AGranuleDroppedOnTheSleepingPileWakesItsNeighboursAndRests) {
  WorldSettings settings = sleepingPileSettings();
  std::uint64_t hashes[2] = {};
  for (std::uint64_t& hash : hashes) {
    testing::TestWorld w(settings);
    buildPile(*w);
    ASSERT_GT(sleepAll(w, 2.0), 0.0);
    // Set down gently, a diameter clear of the pile's top, near one wall.
    const float d = w->settings().particleDiameter;
    float pileTop = 0.0f;
    for (const BodyState& body : w->readBodies()) pileTop = std::max(pileTop, body.position.y);
    w.addGranule({0.07f, pileTop + 3.0f * d, 0.07f}, {}, {0, -0.2f, 0});
    std::uint32_t fewest = kGranules + 1;
    for (int frame = 0; frame < 30; ++frame) {
      w.simulate(0.01);
      fewest = std::min(fewest, w->readStats().granulesAsleep);
    }
    // The impact woke some of the pile, not all of it: a quarter at least stayed asleep.
    std::printf("fewest asleep after the drop: %u of %u\n", fewest, kGranules);
    EXPECT_LT(fewest, kGranules);
    EXPECT_GE(fewest, kGranules / 4);
    // The dropped granule came to rest on the pile: it did not sink through sleeping sand.
    w.simulate(1.0);
    const BodyState dropped = w->readBodies().back();
    EXPECT_LT(std::hypot(dropped.velocity.x, dropped.velocity.y, dropped.velocity.z),
              w->sleepModel().linearSpeed * 10.0f);
    const WorldSnapshot s = w->readSnapshot();
    float top = -1.0f;
    for (std::size_t i = 0; i + 1 < s.bodies.size(); ++i) {
      if (s.bodies[i].alive) top = std::max(top, s.bodies[i].position[1]);
    }
    EXPECT_GT(dropped.position.y, top - 2.0f * d);
    hash = w->readStateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);  // the same sleep and wake pattern, bit for bit
}

// A rock (a body of 33 particles: a ball of radius 2 d on a lattice of spacing d) set down at
// 0.3 m/s onto the middle of a bed of 432 granules three deep in a box 30 d wide, settled (and,
// with sleep, asleep), and left for a second (and RockRun::sleepAgainSeconds more).
struct RockResult {
  double restHeight = 0.0;     // the rock's centre a second after the drop, m
  std::uint32_t moved = 0;     // granules whose position changed at all
  std::uint32_t movedFar = 0;  // of those, the ones farther than kQuietRadius from the rock
  double farthestMoved = 0.0;  // the largest horizontal distance of one of them from the rock, m
  std::uint32_t asleepAtDrop = 0;
  std::uint32_t asleepAtEnd = 0;  // after RockRun::sleepAgainSeconds more
  // With sleep, over the second after the drop: list builds, the builds of the still grid among
  // them, and the most particles a build sorted into its moving grid; then the state hash.
  std::uint64_t listBuilds = 0;
  std::uint64_t stillGridBuilds = 0;
  std::uint32_t mostMovingGridParticles = 0;
  std::uint32_t particles = 0;
  std::uint64_t hash = 0;
  // With `checkContacts`, over the same second: the particle pairs closer than d that a CPU
  // search of every pair found at the end of each of 50 chunks, and those of them that
  // World::readContacts, which reads the lists, did not list, or listed beyond.
  std::uint64_t pairsFound = 0;
  std::uint64_t pairsMissed = 0;
  std::uint64_t pairsExtra = 0;
};

constexpr std::uint32_t kBedGranules = 432;
// Beyond this many diameters from the rock's axis (5.6 rock radii) nothing may wake.
constexpr double kQuietRadius = 14.0;
// How long the sand the rock woke takes to sleep again follows the bits of its settling: a
// second on one driver, 1.5 s on another (Mesa 22.3 and 25.0 on llvmpipe). They are counted two
// seconds after the drop.
constexpr double kSleepAgainSeconds = 1.0;

// Compares the particle pairs of `contacts` with those a CPU search of every pair of particles of
// two bodies finds closer than `d`; pairs within a ten-thousandth of d of touching are left out,
// where the GPU's rounding may decide otherwise.
void comparePairs(const std::vector<ParticleState>& particles,
                  const std::vector<ContactRecord>& contacts, float d, RockResult& r) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> listed;
  for (const ContactRecord& c : contacts) {
    if (c.particleB != ContactRecord::kNone) {
      listed.insert(std::minmax(c.particleA, c.particleB));
    }
  }
  const double edge = 1e-4 * d;
  std::size_t touching = 0;
  for (std::uint32_t a = 0; a < particles.size(); ++a) {
    for (std::uint32_t b = a + 1; b < particles.size(); ++b) {
      if (particles[a].body == particles[b].body) continue;
      const Vec3 p = particles[a].position, q = particles[b].position;
      const double dist = std::hypot(p.x - q.x, p.y - q.y, p.z - q.z);
      if (std::abs(dist - d) < edge) {
        listed.erase({a, b});
        continue;
      }
      if (dist > d) continue;
      ++touching;
      if (listed.erase({a, b}) == 0) ++r.pairsMissed;
    }
  }
  r.pairsFound += touching;
  r.pairsExtra += listed.size();
}

struct RockRun {
  bool sleep = false;
  // Every list build sorts every particle into one grid (testing::useOneGrid).
  bool oneGrid = false;
  // comparePairs after each chunk of the second after the drop.
  bool checkContacts = false;
  // Simulated after that second, before the sleepers are counted again, s.
  double sleepAgainSeconds = 0.0;
};

RockResult dropRock(const RockRun& run) {
  WorldSettings settings = testing::smallSettings(kBedGranules + 1);
  settings.maxParticles = 4 * kBedGranules + 64;
  settings.sleep.enabled = run.sleep;
  // Neither World sorts its granules by place, so that the two differ in sleep alone: a sort
  // changes the order of the sums (with sleep, of the computed granules' only), and the rock's
  // rest height follows such last bits by up to half a diameter.
  settings.sortInterval = kNeverSortGranules;
  testing::TestWorld w(settings);
  if (run.oneGrid) testing::useOneGrid(*w);
  const float d = settings.particleDiameter;
  w->addCollider(Plane{});
  w->addCollider(Box{.center = {0, 0.3f, 0}, .halfExtents = {0.3f, 0.3f, 0.3f}, .inside = true});
  w->addGranules(GranuleBlock{.center = {0, 0.07f, 0},
                              .countX = 12,
                              .countY = 3,
                              .countZ = 12,
                              .velocity = {0, -0.5f, 0},
                              .seed = 5});
  w.simulate(1.6);
  RockResult r;
  r.asleepAtDrop = w->readStats().granulesAsleep;
  const std::vector<BodyState> before = w->readBodies();
  float top = 0.0f;
  for (const BodyState& b : before) top = std::max(top, b.position.y);
  std::vector<Vec3> ball;
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -2; z <= 2; ++z)
        if (x * x + y * y + z * z <= 4) ball.push_back({x * d, y * d, z * d});
  const float rockX = 0.01f, rockZ = -0.005f;
  w->addBody(makeParticleTemplate(ball, d, settings.material.density),
             {{rockX, top + 3.0f * d, rockZ}, {}, {0, -0.3f, 0}, {}, Motion::Dynamic});
  const WorldStats atDrop = w->readStats();
  for (int chunk = 0; chunk < 50; ++chunk) {
    w.simulate(0.02);
    r.mostMovingGridParticles =
        std::max(r.mostMovingGridParticles, w->readStats().movingGridParticles);
    if (run.checkContacts) comparePairs(w->readParticles(), w->readContacts(), d, r);
  }
  const WorldStats atEnd = w->readStats();
  r.listBuilds = atEnd.listBuilds - atDrop.listBuilds;
  r.stillGridBuilds = atEnd.stillGridBuilds - atDrop.stillGridBuilds;
  r.particles = atEnd.particles;
  r.hash = w->readStateHash();
  const std::vector<BodyState> after = w->readBodies();
  r.restHeight = after.back().position.y;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const Vec3 a = before[i].position, b = after[i].position;
    if (std::memcmp(&a, &b, sizeof a) == 0) continue;
    const double away = std::hypot(a.x - rockX, a.z - rockZ);
    ++r.moved;
    if (away > kQuietRadius * d) ++r.movedFar;
    r.farthestMoved = std::max(r.farthestMoved, away);
  }
  if (run.sleepAgainSeconds > 0.0) w.simulate(run.sleepAgainSeconds);
  r.asleepAtEnd = w->readStats().granulesAsleep;
  return r;
}

TEST(Sleep, ARockDroppedOnASleepingBedWakesOnlyItsSurroundingsAndRestsAsWithoutSleep) {
  const RockResult awake = dropRock({});
  const RockResult asleep = dropRock({.sleep = true, .sleepAgainSeconds = kSleepAgainSeconds});
  const double d = testing::smallSettings().particleDiameter;
  std::printf(
      "rock at rest %.3f d up without sleep, %.3f d with; moved: %u of %u granules without sleep "
      "(%u beyond %.0f d), %u with (%u beyond, the farthest %.2f d from the rock's axis); with "
      "sleep %u asleep at the drop, %u two seconds later\n",
      awake.restHeight / d, asleep.restHeight / d, awake.moved, kBedGranules, awake.movedFar,
      kQuietRadius, asleep.moved, asleep.movedFar, asleep.farthestMoved / d, asleep.asleepAtDrop,
      asleep.asleepAtEnd);
  // The rock met a bed nearly all asleep (a few rattlers take longer than the sleep time).
  EXPECT_GE(asleep.asleepAtDrop, kBedGranules * 9 / 10);
  // Without sleep the whole bed feels the rock (a bit at least); with it, only its surroundings
  // wake: beyond kQuietRadius no granule changes a bit.
  ASSERT_GT(awake.movedFar, 0u);
  EXPECT_EQ(asleep.movedFar, 0u);
  EXPECT_GT(asleep.moved, 0u);
  // It digs in and rests where it rests without sleep, to within a quarter of a diameter, and
  // the bed sleeps again under it (as much of it as at the drop, give or take a few rattlers).
  EXPECT_NEAR(asleep.restHeight, awake.restHeight, 0.25 * d);
  EXPECT_GE(asleep.asleepAtEnd, kBedGranules * 9 / 10);
}

// A list build sorts the awake sand, and the sleepers that moved since the sleepers were last
// sorted, into a grid of their own (docs/architecture.md, "Sleep"): the rock's second on the
// sleeping bed. The lists, and so every bit of the result, are those of one grid of every
// particle.
TEST(Sleep, AListBuildSortsTheAwakeSandAndFindsWhatOneGridFinds) {
  const RockResult two = dropRock({.sleep = true});
  const RockResult one = dropRock({.sleep = true, .oneGrid = true});
  std::printf(
      "second after the drop: %llu list builds, %llu of them sorting the sleepers again (%llu "
      "with one grid); at most %u of %u particles in a build's moving grid\n",
      static_cast<unsigned long long>(two.listBuilds),
      static_cast<unsigned long long>(two.stillGridBuilds),
      static_cast<unsigned long long>(one.stillGridBuilds), two.mostMovingGridParticles,
      two.particles);
  ASSERT_GT(two.listBuilds, 2u);
  EXPECT_EQ(one.stillGridBuilds, one.listBuilds);
  EXPECT_LT(two.stillGridBuilds, two.listBuilds / 2);
  EXPECT_GT(two.mostMovingGridParticles, 0u);
  EXPECT_LT(two.mostMovingGridParticles, two.particles / 2);
  EXPECT_EQ(two.hash, one.hash);
  EXPECT_EQ(two.restHeight, one.restHeight);
}

// A sleeper that something awake touches after the list build that passed over it finds its
// partners in that build's grid and builds its list there and then, for the substeps until the
// next build (docs/architecture.md, "Sleep"). Those lists must hold every contact: over the
// rock's second on the sleeping bed, the contacts read from the lists are the pairs closer than
// d that a CPU search of every pair finds.
TEST(Sleep, TheListsOfTouchedSleepersHoldEveryContactACpuSearchFinds) {
  const RockResult r = dropRock({.sleep = true, .checkContacts = true});
  std::printf(
      "second after the drop: %llu touching pairs found by the CPU in 50 checks, %llu "
      "of them not listed, %llu listed beyond them\n",
      static_cast<unsigned long long>(r.pairsFound), static_cast<unsigned long long>(r.pairsMissed),
      static_cast<unsigned long long>(r.pairsExtra));
  ASSERT_GT(r.pairsFound, 50u * kBedGranules);
  EXPECT_EQ(r.pairsMissed, 0u);
  EXPECT_EQ(r.pairsExtra, 0u);
}

TEST(Sleep, SnapshotCarriesTheSleepState) {
  testing::TestWorld a(sleepingPileSettings());
  buildPile(*a);
  a.simulate(0.5);
  const WorldSnapshot middle = a->readSnapshot();
  testing::TestWorld b(sleepingPileSettings());
  buildPile(*b);
  b->restoreSnapshot(middle);
  EXPECT_FALSE(firstDifference(middle, b->readSnapshot()).has_value());
  EXPECT_EQ(stateHash(middle), a->readStateHash());
  a.simulate(1.0);
  b.simulate(1.0);
  EXPECT_EQ(a->readStateHash(), b->readStateHash());
  EXPECT_GT(a->readStats().granulesAsleep, 0u);
}

// A sleeper keeps the forces of the substep that last computed it, and the balance check of one
// that something awake touches sums them: a snapshot of a pile half asleep carries them, so a
// restored World goes on bit for bit (without them its touched sleepers saw no force, only
// gravity, and woke the whole pile).
TEST(Sleep, ARestoredHalfSleepingPileGoesOnBitForBit) {
  testing::TestWorld a(sleepingPileSettings());
  buildPile(*a);
  std::uint32_t asleep = 0;
  while (a->simulatedTime() < 1.5 && asleep < kGranules / 3) {
    a.simulate(0.05);
    asleep = a->readStats().granulesAsleep;
  }
  ASSERT_GE(asleep, kGranules / 3);
  ASSERT_LT(asleep, kGranules) << "the pile slept before a snapshot caught it half asleep";
  const WorldSnapshot middle = a->readSnapshot();
  ASSERT_EQ(middle.forces.size(), middle.contacts.size());
  EXPECT_EQ(a->readStateHash(), stateHash(middle));
  testing::TestWorld b(sleepingPileSettings());
  buildPile(*b);
  b->restoreSnapshot(middle);
  EXPECT_FALSE(firstDifference(middle, b->readSnapshot()).has_value());
  for (int k = 0; k < 4; ++k) {
    a->substep(50);
    b->substep(50);
    const auto difference = firstDifference(a->readSnapshot(), b->readSnapshot());
    ASSERT_FALSE(difference.has_value())
        << "after " << 50 * (k + 1) << " substeps, " << difference->describe();
  }
  EXPECT_EQ(a->readStateHash(), b->readStateHash());
  EXPECT_EQ(a->readStats().granulesAsleep, b->readStats().granulesAsleep);
  EXPECT_GE(b->readStats().granulesAsleep, asleep);
}

// A granule dropped on the sleeping pile wakes part of it, and builds pass over the sleepers'
// lists; a touched sleeper whose list a build passed over finds its partners in the grid. Whether
// its contacts stay frozen must not depend on that (a restored World builds every list afresh): a
// World restored at any moment of the impact goes on bit for bit.
TEST(Sleep, ARestoreDuringAnImpactGoesOnBitForBit) {
  testing::TestWorld a(sleepingPileSettings());
  buildPile(*a);
  ASSERT_GT(sleepAll(a, 2.0), 0.0);
  const float d = a->settings().particleDiameter;
  float pileTop = 0.0f;
  for (const BodyState& body : a->readBodies()) pileTop = std::max(pileTop, body.position.y);
  const Vec3 dropAt{0.07f, pileTop + 3.0f * d, 0.07f};
  a.addGranule(dropAt, {}, {0, -0.2f, 0});
  std::uint32_t fewest = kGranules;
  for (int moment = 0; moment < 5; ++moment) {
    a.simulate(0.03);
    const WorldSnapshot then = a->readSnapshot();
    testing::TestWorld b(sleepingPileSettings());
    buildPile(*b);
    b.addGranule(dropAt, {}, {0, -0.2f, 0});
    b->restoreSnapshot(then);
    for (int k = 0; k < 150; k += 10) {
      a->substep(10);
      b->substep(10);
      const auto difference = firstDifference(a->readSnapshot(), b->readSnapshot());
      ASSERT_FALSE(difference.has_value()) << "restored at " << then.simulatedTime << " s, after "
                                           << k + 10 << " substeps: " << difference->describe();
    }
    fewest = std::min(fewest, a->readStats().granulesAsleep);
  }
  EXPECT_LT(fewest, kGranules);  // the impact woke some
  EXPECT_GT(fewest, 0u);
}

// A sleeping particle is not computed, so it reports the contacts it counted last: a World that
// restores a sleeping pile counts those its contact history holds, as the World that saved it.
TEST(Sleep, ARestoredSleepingPileCountsTheContactsItSleepsWith) {
  testing::TestWorld a(sleepingPileSettings());
  buildPile(*a);
  a.simulate(1.5);
  const WorldStats saved = a->readStats();
  ASSERT_EQ(saved.granulesAsleep, 96u);
  testing::TestWorld b(sleepingPileSettings());
  buildPile(*b);
  b->restoreSnapshot(a->readSnapshot());
  EXPECT_EQ(b->readStats().contacts, saved.contacts);
  b->substep(10);
  a->substep(10);
  const WorldStats restored = b->readStats();
  EXPECT_EQ(restored.granulesAsleep, 96u);
  EXPECT_EQ(restored.contacts, a->readStats().contacts);
  EXPECT_GT(restored.contacts, 200u);
}

// A column of sand between four walls, whose +x wall is taken away once it has settled (and,
// with sleep, fallen asleep): how far the slumped sand runs out, and how many granules slept at
// the cut.
struct CutResult {
  // Where the front of the slumped sand lies: the 90th percentile of the granules' x (m). The
  // largest x, one granule's luck, varies by more than 2 d between runs that differ in a bit.
  double runOut = 0.0;
  double farthest = 0.0;  // the largest x, m
  std::uint32_t asleepAtCut = 0;
  std::uint32_t asleepAtEnd = 0;
};

CutResult cutColumn(bool sleep) {
  // With rolling friction, as buildPile's pile, so that the column sleeps whole on every
  // trajectory tried.
  WorldSettings settings = sleepingPileSettings();
  settings.sleep.enabled = sleep;
  testing::TestWorld w(settings);
  const float half = 0.07f;
  w->addCollider(Plane{});
  const ColliderId wall = w->addCollider(Plane{{-1, 0, 0}, -half});
  w->addCollider(Plane{{1, 0, 0}, -half});
  w->addCollider(Plane{{0, 0, -1}, -half});
  w->addCollider(Plane{{0, 0, 1}, -half});
  w->addGranules(GranuleBlock{.center = {0, 0.12f, 0},
                              .countX = 4,
                              .countY = 6,
                              .countZ = 4,
                              .velocity = {0, -1.5f, 0},
                              .seed = 11});
  w.simulate(1.6);
  CutResult r;
  r.asleepAtCut = w->readStats().granulesAsleep;
  w->setCollider(wall, Plane{{-1, 0, 0}, -10.0f});
  w.simulate(1.5);
  r.asleepAtEnd = w->readStats().granulesAsleep;
  std::vector<double> x;
  for (const BodyState& b : w->readBodies()) x.push_back(b.position.x);
  std::sort(x.begin(), x.end());
  r.runOut = x[x.size() * 9 / 10];
  r.farthest = x.back();
  return r;
}

TEST(Sleep, AColumnCutAtItsFootRunsOutAsWithoutSleep) {
  const CutResult awake = cutColumn(false);
  const CutResult asleep = cutColumn(true);
  const double d = testing::smallSettings().particleDiameter;
  std::printf(
      "run-out (90th percentile of x) %.2f d without sleep, %.2f d with (farthest granule "
      "%.2f d, %.2f d; %u of %u asleep at the cut, %u at the end)\n",
      awake.runOut / d, asleep.runOut / d, awake.farthest / d, asleep.farthest / d,
      asleep.asleepAtCut, kGranules, asleep.asleepAtEnd);
  ASSERT_EQ(asleep.asleepAtCut, kGranules);  // the cut met a sleeping column
  // The wall was at 3.5 d; the front ran out past it, and as far as without sleep to within the
  // spread of a slump of 96 granules.
  EXPECT_GT(awake.runOut, 0.07 + 2.0 * d);
  EXPECT_NEAR(asleep.runOut, awake.runOut, 2.0 * d);
}

// The pile of buildPile asleep; its highest granule on the side away from where the events below
// drop a granule; that granule lifted by less than half the list skin, so that no list build
// (which scans every chunk) follows; the state 20 ms after the lift; and the time step.
struct SleptPile {
  WorldSnapshot slept;
  BodyState top;
  BodyDesc lifted;
  WorldSnapshot stirred;
  float timeStep = 0.0f;  // s, the World's
};

void sleepPile(const WorldSettings& settings, SleptPile& out) {
  testing::TestWorld pile(settings);
  buildPile(*pile);
  ASSERT_GT(sleepAll(pile, 2.0), 0.0);
  out.slept = pile->readSnapshot();
  const std::vector<BodyState> bodies = pile->readBodies();
  out.top = *std::ranges::max_element(
      bodies, {}, [](const BodyState& s) { return s.position.x < 0.0f ? s.position.y : -1.0f; });
  out.lifted = {.position = out.top.position + Vec3{0.0f, 0.05f * settings.particleDiameter, 0.0f},
                .orientation = out.top.orientation};
  pile->setBodyState(out.top.id, out.lifted);
  pile.simulate(0.02);
  out.stirred = pile->readSnapshot();
  out.timeStep = pile->timeStep();
}

// Events both comparisons below do to the sleeping pile: `compare(event, seconds, doTo)` with
// the top sleeper set elsewhere, a state restored with it awake, and a corner woken.
template <class Compare>
void liftRestoreAndWake(const SleptPile& pile, const Compare& compare) {
  compare("the highest sleeper lifted", 0.05,
          [&](testing::TestWorld& w) { w->setBodyState(pile.top.id, pile.lifted); });
  compare("a state restored with that sleeper awake", 0.05,
          [&](testing::TestWorld& w) { w->restoreSnapshot(pile.stirred); });
  compare("a corner woken", 0.05, [&](testing::TestWorld& w) {
    w->wake({-1, -1, 0.05f}, {-0.05f, 1, 1});
  });
}

// collect_active.comp passes over a chunk of bodies it found quiet (none computed) until
// something may have changed it: an awake particle touching a sleeper in it, the CPU adding,
// setting or restoring bodies, World::wake, a collider moved. Each of these, done to the sleeping
// pile, gives the bits of a World that scans every chunk in every substep (and each fails
// without its part of the invalidation).
TEST(Sleep, PassingOverQuietChunksChangesNoBit) {
  const float d = sleepingPileSettings().particleDiameter;
  SleptPile pile;
  ASSERT_NO_FATAL_FAILURE(sleepPile(sleepingPileSettings(), pile));
  const BodyState& top = pile.top;
  // The sleeping pile, once the chunks are found quiet again: the event, done to both Worlds,
  // then `seconds` compared every 25 ms.
  const auto compare = [&](const char* event, double seconds, const auto& doTo) {
    testing::TestWorld a(sleepingPileSettings());
    testing::TestWorld b(sleepingPileSettings());
    testing::scanEveryChunk(*b);
    for (testing::TestWorld* w : {&a, &b}) {
      buildPile(**w);
      (*w)->restoreSnapshot(pile.slept);
      w->simulate(0.005);
      doTo(*w);
    }
    std::uint32_t fewest = kGranules;
    for (double t = 0.025; t < seconds + 1e-9; t += 0.025) {
      a.simulate(0.025);
      b.simulate(0.025);
      const auto difference = firstDifference(a->readSnapshot(), b->readSnapshot());
      ASSERT_FALSE(difference.has_value())
          << event << ", " << t << " s after: " << difference->describe();
      fewest = std::min(fewest, a->readStats().granulesAsleep);
    }
    std::printf("%s: at least %u of %u granules stayed asleep\n", event, fewest, kGranules);
    EXPECT_LT(fewest, kGranules) << event << " woke nothing";
  };
  // The granule joins a quiet chunk (that of a static sphere added first, out of reach) and
  // lands after about 60 ms, on sleepers in quiet chunks.
  compare("a granule dropped on the pile", 0.1, [&](testing::TestWorld& w) {
    const WorldSettings& s = w->settings();
    w->addBody(makeParticleTemplate({{0.0f, 0.0f, 0.0f}}, d, s.material.density),
               {.position = {0.09f, 0.5f, 0.09f}, .motion = Motion::Static});
    w.simulate(0.005);
    const BodyDesc granule{.position = {0.07f, top.position.y + 3.0f * d, 0.07f},
                           .velocity = {0, -0.2f, 0}};
    w->addGranules(std::span(&granule, 1));
  });
  liftRestoreAndWake(pile, compare);
  compare("a paddle let down onto the pile", 0.05, [&](testing::TestWorld& w) {
    const Box paddle{.center = {-0.05f, top.position.y + 2.5f * d, 0.0f},
                     .halfExtents = {0.04f, 0.5f * d, 0.08f},
                     .inside = false};
    const ColliderId id = w->addCollider(paddle);
    w.simulate(0.005);
    Box lowered = paddle;
    lowered.center.y -= 1.5f * d;
    w->setCollider(id, lowered);
  });
}

// The first field in which two WorldStats differ, bit for bit, or nullptr.
const char* firstStatsDifference(const WorldStats& a, const WorldStats& b) {
  static_assert(sizeof(WorldStats) == 144, "a field was added to WorldStats: compare it below");
  const std::pair<const char*, bool> same[] = {
      {"bodies", a.bodies == b.bodies},
      {"particles", a.particles == b.particles},
      {"granulesSpawned", a.granulesSpawned == b.granulesSpawned},
      {"granulesAlive", a.granulesAlive == b.granulesAlive},
      {"granulesAsleep", a.granulesAsleep == b.granulesAsleep},
      {"granulesKilled", a.granulesKilled == b.granulesKilled},
      {"granulesNotBorn", a.granulesNotBorn == b.granulesNotBorn},
      {"contacts", a.contacts == b.contacts},
      {"gridBuckets", a.gridBuckets == b.gridBuckets},
      {"listBuilds", a.listBuilds == b.listBuilds},
      {"listNearMarkings", a.listNearMarkings == b.listNearMarkings},
      {"neighbourListOverflows", a.neighbourListOverflows == b.neighbourListOverflows},
      {"granuleSorts", a.granuleSorts == b.granuleSorts},
      {"stillGridBuilds", a.stillGridBuilds == b.stillGridBuilds},
      {"movingGridParticles", a.movingGridParticles == b.movingGridParticles},
      {"kineticEnergy", a.kineticEnergy == b.kineticEnergy},
      {"maxOverlap", a.maxOverlap == b.maxOverlap},
      {"penetrationClamps", a.penetrationClamps == b.penetrationClamps},
      {"contactSlotOverflows", a.contactSlotOverflows == b.contactSlotOverflows},
      {"velocityClamps", a.velocityClamps == b.velocityClamps},
      {"steps", a.steps == b.steps},
      {"simulatedTime", a.simulatedTime == b.simulatedTime},
  };
  for (const auto& [field, equal] : same) {
    if (!equal) return field;
  }
  return nullptr;
}

// World::step skips the substeps of a frame whose first substep finds all the sand asleep and
// untouched (StepReport::idleSubsteps), and then reads the statistics of the last reduce while
// nothing they read has changed, also when the skipped substeps would sort the granules. Against a
// World that runs every substep (World::substep) and reduces its statistics from every particle
// each frame, after each kind of event that wakes sand or waits on later substeps, the two keep the
// same bits frame by frame, and the same statistics (read straight after the event too); and the
// sleeping pile, once a frame's first substep has found it so, runs no substep and reduces no
// statistics.
TEST(Sleep, FramesOfSleepingSandRunOneSubstepAndChangeNoBit) {
  WorldSettings settings = sleepingPileSettings();
  settings.statsEachFrame = true;  // the statistics compared each frame, and the idle hint
  const float d = settings.particleDiameter;
  SleptPile pile;
  ASSERT_NO_FATAL_FAILURE(sleepPile(settings, pile));
  // The compared Worlds sort their granules every 100 substeps, so that each frame has a sort:
  // one that computes nothing sorts nothing, as the frame that skips it.
  settings.sortInterval = 100;
  const BodyState& top = pile.top;
  struct Skipped {
    std::uint32_t substeps = 0;
    std::uint32_t idleSubsteps = 0;
    std::uint64_t statsReductions = 0;
  };
  // Frames of 10 ms: three of the sleeping pile, then the event, done to both Worlds, and
  // `seconds` more; returns what the framed World skipped after the event.
  const auto compare = [&](const char* event, double seconds, const auto& doTo) {
    testing::TestWorld framed(settings);
    testing::TestWorld every(settings);
    for (testing::TestWorld* w : {&framed, &every}) {
      buildPile(**w);
      (*w)->restoreSnapshot(pile.slept);
    }
    const auto sameStats = [&](const WorldStats& stats, const std::string& when) {
      const char* field = firstStatsDifference(stats, testing::reduceStats(*every));
      if (field) ADD_FAILURE() << event << ", " << when << ": WorldStats::" << field;
      return field == nullptr;
    };
    Skipped skipped;
    std::uint64_t reductionsBefore = 0;
    const int frames = int(std::lround(seconds / 0.01));
    for (int frame = -3; frame < frames; ++frame) {
      if (frame == 0) {
        doTo(framed);
        doTo(every);
        reductionsBefore = testing::statsReductions(*framed);
        if (!sameStats(framed->readStats(), "read straight after")) break;
        skipped.idleSubsteps = skipped.substeps = 0;
      }
      const StepReport report = framed->step(0.01f);
      every->resetPeakOverlap();  // as each step does
      every->substep(report.substeps);
      skipped.substeps += report.substeps;
      skipped.idleSubsteps += report.idleSubsteps;
      if (report.idleSubsteps > 0) {
        EXPECT_GE(report.idleSubsteps, report.substeps - 1) << event;
      }
      const auto difference = firstDifference(framed->readSnapshot(), every->readSnapshot());
      if (difference || framed->readStateHash() != every->readStateHash() ||
          framed->stepCount() != every->stepCount()) {
        ADD_FAILURE() << event << ", frame " << frame << " after: "
                      << (difference ? difference->describe() : "the hash or the step count");
        break;
      }
      if (!report.hasStats || !sameStats(report.stats, "frame " + std::to_string(frame) + " after"))
        break;
    }
    skipped.statsReductions = testing::statsReductions(*framed) - reductionsBefore;
    std::printf("%s: %u of %u substeps skipped as idle, %llu of %d frames reduced statistics\n",
                event, skipped.idleSubsteps, skipped.substeps,
                static_cast<unsigned long long>(skipped.statsReductions), frames);
    return skipped;
  };
  const auto nothing = [](testing::TestWorld&) {};
  // Asleep: the frame after the one whose statistics said the sand slept runs one substep, and
  // every frame after that none; all read the statistics they kept.
  const Skipped asleep = compare("asleep", 0.1, nothing);
  EXPECT_EQ(asleep.idleSubsteps, asleep.substeps);
  EXPECT_EQ(asleep.statsReductions, 0u);
  // Events between frames that wake sand, or place bodies, colliders or states: the first
  // substep of the next frame sees them, and the statistics are reduced again.
  compare("a granule dropped on the pile", 0.1, [&](testing::TestWorld& w) {
    const BodyDesc granule{.position = {0.07f, top.position.y + 3.0f * d, 0.07f},
                           .velocity = {0, -0.2f, 0}};
    w->addGranules(std::span(&granule, 1));
  });
  liftRestoreAndWake(pile, compare);
  compare("a paddle set down onto the pile", 0.05, [&](testing::TestWorld& w) {
    w->addCollider(Box{.center = {-0.05f, top.position.y + 1.3f * d, 0.0f},
                       .halfExtents = {0.04f, 0.5f * d, 0.08f},
                       .inside = false});
  });
  // CPU work that waits for later substeps: no frame skips while it runs.
  const Skipped emitting = compare("an emitter over the pile", 0.05, [&](testing::TestWorld& w) {
    w->addEmitter({.center = {0.0f, top.position.y + 4.0f * d, 0.0f},
                   .halfExtentX = 0.05f,
                   .halfExtentZ = 0.05f,
                   .rate = 100.0f,
                   .velocity = {0.0f, -1.0f, 0.0f},
                   .maxGranules = 4});
  });
  EXPECT_EQ(emitting.idleSubsteps, 0u);
}

// Two copies of one World: `framed` runs frames of World::step, which skips idle substeps,
// `every` the same substeps through World::substep, which skips none. After each frame the two
// must hold the same bits, and the same force sums on their large bodies (World::takeBodyForces).
struct Lockstep {
  testing::TestWorld framed;
  testing::TestWorld every;
  explicit Lockstep(const WorldSettings& settings) : framed(settings), every(settings) {}

  template <class DoTo>
  void both(const DoTo& doTo) {
    doTo(framed);
    doTo(every);
  }

  // One frame of `seconds`; the forces taken from `framed`.
  StepReport frame(double seconds, const std::string& when, std::vector<BodyForce>& forces) {
    const StepReport report = framed->step(float(seconds));
    every->resetPeakOverlap();  // as each step does
    every->substep(report.substeps);
    const auto difference = firstDifference(framed->readSnapshot(), every->readSnapshot());
    EXPECT_FALSE(difference.has_value()) << when << ": " << difference->describe();
    EXPECT_EQ(framed->readStateHash(), every->readStateHash()) << when;
    forces = framed->takeBodyForces();
    const std::vector<BodyForce> oracle = every->takeBodyForces();
    EXPECT_EQ(forces.size(), oracle.size()) << when;
    for (std::size_t i = 0; i < std::min(forces.size(), oracle.size()); ++i) {
      EXPECT_EQ(forces[i].substeps, oracle[i].substeps) << when << ", body " << i;
      EXPECT_EQ(std::memcmp(&forces[i].force, &oracle[i].force, sizeof(Vec3)), 0) << when;
      EXPECT_EQ(std::memcmp(&forces[i].torque, &oracle[i].torque, sizeof(Vec3)), 0) << when;
    }
    return report;
  }
};

// Body `body`'s calm count in `w` (snapshot.h: asleep at SleepModel::substeps).
std::uint32_t calmOf(World& w, BodyId body) {
  return w.readSnapshot().bodies.at(body.index).calm;
}

TEST(Sleep, AKinematicBodySetAtRestEveryFrameLeavesTheSandAsleep) {
  // What an engine bridge does with a body that rests: it sets the same pose, at rest, every
  // frame. The sand that settled around it must sleep and stay asleep. Once the engine stops
  // setting it (as the bridge does when Bullet puts the body to sleep), the body sleeps too, and
  // the World's frames run no substep. Without statistics each frame (testing::smallSettings), as
  // a game that reads none.
  const WorldSettings settings = sleepingPileSettings();
  ASSERT_FALSE(settings.statsEachFrame);
  Lockstep w(settings);
  const float d = settings.particleDiameter;
  const BodyDesc post{{0.0f, 1.5f * d, 0.0f}, {}, {}, {}, Motion::Kinematic};
  BodyId body;
  w.both([&](testing::TestWorld& t) {
    body =
        t->addBody(makeParticleTemplate({{0.0f, 0.0f, 0.0f}}, d, settings.material.density), post);
    buildPile(*t);
    ASSERT_GT(sleepAll(t, 2.0), 0.0);
  });
  const std::vector<BodyState> slept = w.framed->readBodies();
  std::vector<BodyForce> forces;
  for (int frame = 0; frame < 20; ++frame) {
    w.both([&](testing::TestWorld& t) { t->setBodyState(body, post); });
    w.frame(0.02, "set at rest, frame " + std::to_string(frame), forces);
    // Set awake, one short of sleep: computed at least once a frame.
    ASSERT_EQ(forces.size(), 1u);
    EXPECT_GT(forces[0].substeps, 0u) << frame;
  }
  EXPECT_EQ(w.framed->readStats().granulesAsleep, kGranules);
  const std::vector<BodyState> after = w.framed->readBodies();
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(std::memcmp(&after[i].position, &slept[i].position, sizeof(Vec3)), 0) << i;
  }
  const std::uint32_t sleepSubsteps = w.framed->sleepModel().substeps;
  EXPECT_GE(calmOf(*w.framed, body), sleepSubsteps);
  std::uint32_t substeps = 0;
  std::uint32_t idle = 0;
  for (int frame = 0; frame < 10; ++frame) {
    const StepReport report = w.frame(0.02, "left alone, frame " + std::to_string(frame), forces);
    // The first frame runs one substep, which finds nothing to compute; the rest run none.
    EXPECT_EQ(report.idleSubsteps, frame == 0 ? report.substeps - 1 : report.substeps) << frame;
    EXPECT_EQ(forces.at(0).substeps, 0u) << frame;
    substeps += report.substeps;
    idle += report.idleSubsteps;
  }
  std::printf("the post left alone at rest: %u of %u substeps skipped as idle\n", idle, substeps);
}

// Without statistics each frame, what tells a frame that the last one ended with the sand asleep
// is a copy of the counters that the frame's end starts and the next frame takes if the GPU has
// made it, never waiting (World::Impl::idleHint): the sleeping pile's first frame runs whole, the
// second checks its first substep and skips the rest, and the frames after run none; no
// statistics are reduced, and every frame has the bits of a World that runs every substep.
TEST(Sleep, FramesOfSleepingSandSkipWithoutStatisticsEachFrame) {
  const WorldSettings settings = sleepingPileSettings();
  ASSERT_FALSE(settings.statsEachFrame);
  SleptPile pile;
  ASSERT_NO_FATAL_FAILURE(sleepPile(settings, pile));
  Lockstep w(settings);
  w.both([&](testing::TestWorld& t) {
    buildPile(*t);
    t->restoreSnapshot(pile.slept);
  });
  const std::uint64_t reductions = testing::statsReductions(*w.framed);
  std::vector<BodyForce> forces;
  std::uint32_t substeps = 0;
  std::uint32_t idle = 0;
  for (int frame = 0; frame < 10; ++frame) {
    const StepReport report = w.frame(0.01, "frame " + std::to_string(frame), forces);
    const std::uint32_t expected = frame == 0   ? 0u
                                   : frame == 1 ? report.substeps - 1
                                                : report.substeps;
    EXPECT_EQ(report.idleSubsteps, expected) << "frame " << frame;
    substeps += report.substeps;
    idle += report.idleSubsteps;
  }
  EXPECT_EQ(testing::statsReductions(*w.framed), reductions);
  EXPECT_EQ(w.framed->readStats().granulesAsleep, kGranules);
  std::printf("the sleeping pile without statistics each frame: %u of %u substeps skipped\n", idle,
              substeps);
}

// A rock (a dynamic body of seven particles, not a granule) set down on the sleeping pile comes to
// rest and falls asleep with the sand it woke; then the World's frames run no substep and the
// rock gains no force sum. A granule dropped onto it wakes it, and all sleeps again. Every frame
// is compared bit for bit with a World that runs every substep.
TEST(Sleep, ARockAtRestSleepsWithTheSandAndWakesWhenTouched) {
  WorldSettings settings = sleepingPileSettings();
  settings.statsEachFrame = true;  // the hint from the statistics (the post above: without)
  const float d = settings.particleDiameter;
  SleptPile pile;
  ASSERT_NO_FATAL_FAILURE(sleepPile(settings, pile));
  Lockstep w(settings);
  std::vector<Vec3> ball;
  for (int axis = 0; axis < 3; ++axis) {
    for (float side : {-d, d}) {
      Vec3 offset{};
      (axis == 0 ? offset.x : axis == 1 ? offset.y : offset.z) = side;
      ball.push_back(offset);
    }
  }
  ball.push_back({});
  const Vec3 dropAt{0.02f, pile.top.position.y + 3.0f * d, 0.0f};
  BodyId rock;
  w.both([&](testing::TestWorld& t) {
    buildPile(*t);
    t->restoreSnapshot(pile.slept);
    rock = t->addBody(makeParticleTemplate(ball, d, settings.material.density),
                      {.position = dropAt, .velocity = {0.0f, -0.2f, 0.0f}});
  });
  const std::uint32_t sleepSubsteps = w.framed->sleepModel().substeps;
  // Frames of 10 ms until the rock and every granule sleep, then `idleFrames` more, which must
  // run no substep but the first's; returns the seconds it took to sleep, or -1.
  const auto settle = [&](const char* stage, int idleFrames) {
    std::vector<BodyForce> forces;
    for (int frame = 0; frame < 300; ++frame) {
      w.frame(0.01, std::string(stage) + ", frame " + std::to_string(frame), forces);
      if (::testing::Test::HasFailure()) return -1.0;
      const WorldStats stats = w.framed->readStats();
      if (calmOf(*w.framed, rock) < sleepSubsteps || stats.granulesAsleep != stats.granulesAlive)
        continue;
      for (int after = 0; after < idleFrames; ++after) {
        const StepReport report =
            w.frame(0.01, std::string(stage) + ", asleep, frame " + std::to_string(after), forces);
        EXPECT_GE(report.idleSubsteps + 1, report.substeps) << stage << ", " << after;
        if (after > 0) {
          EXPECT_EQ(report.idleSubsteps, report.substeps) << stage << ", " << after;
        }
        EXPECT_EQ(forces.at(0).substeps, 0u) << stage << ", asleep, frame " << after;
      }
      return 0.01 * (frame + 1);
    }
    return -1.0;
  };
  const double restedAfter = settle("the rock set down", 5);
  ASSERT_GT(restedAfter, 0.0) << "the rock, or the sand, never slept";
  const Vec3 rested = w.framed->readBodies().at(rock.index).position;
  // A granule onto the rock: it is touched, computed, and woken by the impact.
  const BodyDesc granule{.position = rested + Vec3{0.0f, 3.0f * d, 0.0f},
                         .velocity = {0.0f, -0.5f, 0.0f}};
  w.both([&](testing::TestWorld& t) { t->addGranules(std::span(&granule, 1)); });
  bool woke = false;
  std::vector<BodyForce> forces;
  for (int frame = 0; frame < 10 && !woke; ++frame) {
    w.frame(0.01, "a granule dropped on the rock, frame " + std::to_string(frame), forces);
    woke = calmOf(*w.framed, rock) < sleepSubsteps;
  }
  EXPECT_TRUE(woke) << "the granule did not wake the rock";
  const double restedAgainAfter = settle("the rock hit", 5);
  EXPECT_GT(restedAgainAfter, 0.0) << "the rock, or the sand, never slept again";
  const Vec3 end = w.framed->readBodies().at(rock.index).position;
  std::printf(
      "the rock slept with the sand %.2f s after it was set down, and again %.2f s after the "
      "granule; it moved %.3f d\n",
      restedAfter, restedAgainAfter,
      std::hypot(end.x - rested.x, end.y - rested.y, end.z - rested.z) / d);
}

}  // namespace
}  // namespace sandphys
