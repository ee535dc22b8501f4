// The determinism contract: the same scene and inputs give bit-identical state on the same device
// and driver, across runs and across worlds in one process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::buildPile;

bool identical(const std::vector<BodyState>& a, const std::vector<BodyState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(&a[i].position, &b[i].position, sizeof(Vec3)) ||
        std::memcmp(&a[i].orientation, &b[i].orientation, sizeof(Quat)) ||
        std::memcmp(&a[i].velocity, &b[i].velocity, sizeof(Vec3)) ||
        std::memcmp(&a[i].angularVelocity, &b[i].angularVelocity, sizeof(Vec3))) {
      return false;
    }
  }
  return true;
}

TEST(Determinism, SameSceneTwiceIsBitIdenticalAfter1000Steps) {
  std::vector<BodyState> first, second;
  for (auto* out : {&first, &second}) {
    testing::TestWorld w;
    buildPile(*w);
    w->substep(1000);
    *out = w->readBodies();
  }
  ASSERT_TRUE(identical(first, second));
  // ... and the granules did interact (a pile, not free flight).
  testing::TestWorld w;
  buildPile(*w);
  w->substep(1000);
  EXPECT_GT(w->readStats().contacts, 30u);
}

TEST(Determinism, TwoWorldsSideBySideAgreeBitForBit) {
  testing::TestWorld a, b;
  buildPile(*a);
  buildPile(*b);
  for (int i = 0; i < 10; ++i) {  // interleaved, sharing one context
    a->substep(100);
    b->substep(100);
  }
  EXPECT_TRUE(identical(a->readBodies(), b->readBodies()));
}

TEST(Determinism, CapacityDoesNotChangeTheResult) {
  // A World with room for a thousand times more granules computes the same pile bit for bit, and
  // scans the same grid table every substep: the table follows the particles in use.
  testing::TestWorld exact(testing::smallSettings(96));
  testing::TestWorld roomy(testing::smallSettings(96 * 1024));
  buildPile(*exact);
  buildPile(*roomy);
  exact->substep(300);
  roomy->substep(300);
  EXPECT_TRUE(identical(exact->readBodies(), roomy->readBodies()));
  EXPECT_GT(exact->readStats().contacts, 30u);
  EXPECT_EQ(roomy->readStats().gridBuckets, exact->readStats().gridBuckets);
  // ... and grows with what is added: past the smallest table's 4096 particles, twice as big.
  const std::uint32_t before = roomy->readStats().gridBuckets;
  for (std::uint32_t layer = 0; layer < 16; ++layer) {
    roomy->addGranules(GranuleBlock{.center = {0, 0.6f + 0.1f * float(layer), 0},
                                    .countX = 8,
                                    .countY = 1,
                                    .countZ = 8,
                                    .seed = 20u + layer});
  }
  roomy->substep(1);
  EXPECT_EQ(roomy->readStats().gridBuckets, 2 * before);
}

TEST(Determinism, TheListSkinDoesNotChangeTheResult) {
  // Contacts are summed in partner order whenever the neighbour lists were built: a thin skin
  // (lists built often), the derived one and a whole diameter (built rarely, and so many
  // candidates that lists overflow into the grid) give the same pile and contact history to the
  // bit. Between sorts of the granules only: a sort takes its order from the grid, whose cells
  // are d + skin wide, so after one the skin changes the order of the sums.
  const float d = testing::smallSettings().particleDiameter;
  struct Run {
    float skin;
    std::vector<BodyState> bodies;
    std::uint64_t hash = 0;
    WorldStats stats;
  };
  std::vector<Run> runs{{0.05f * d}, {0.0f}, {d}};
  for (Run& run : runs) {
    WorldSettings s = testing::smallSettings();
    s.listSkin = run.skin;
    s.sortInterval = kNeverSortGranules;
    testing::TestWorld w(s);
    buildPile(*w);
    w->substep(600);
    run.bodies = w->readBodies();
    run.hash = w->readStateHash();
    run.stats = w->readStats();
    std::printf("[ lists ] skin %.3g d: %llu builds in 600 substeps, %llu particles overflowed\n",
                w->contactModel().listSkin / d,
                static_cast<unsigned long long>(run.stats.listBuilds),
                static_cast<unsigned long long>(run.stats.neighbourListOverflows));
  }
  for (const Run& run : runs) {
    EXPECT_TRUE(identical(runs[0].bodies, run.bodies)) << "skin " << run.skin;
    EXPECT_EQ(runs[0].hash, run.hash) << "skin " << run.skin;
  }
  EXPECT_GT(runs[0].stats.contacts, 30u);
  // The thin skin's lists did not serve the whole run, nor the whole diameter's every substep.
  EXPECT_GT(runs[0].stats.listBuilds, 4 * runs[2].stats.listBuilds);
  EXPECT_LT(runs[2].stats.listBuilds, 300u);
  EXPECT_GT(runs[2].stats.neighbourListOverflows, 0u) << "the grid's share is not exercised";
}

// Without sleep the contacts passes test only the entries of a list marked near (within d + near
// skin when last marked; list_near.comp), marked again once some particle has moved half the near
// skin. Every bit of the state is that of every particle testing every candidate in the grid:
// through a fall, with a skin roomy enough that the near part is marked many times between builds.
TEST(Determinism, ContactsFromTheListsNearPartAreThoseOfEveryParticleSearched) {
  WorldSettings s = testing::smallSettings();
  s.listSkin = 0.4f * s.particleDiameter;
  testing::TestWorld some(s), every(s);
  testing::searchEveryParticle(*every);
  for (testing::TestWorld* w : {&some, &every}) {
    buildPile(**w);
    (*w)->substep(1500);
  }
  const WorldStats stats = some->readStats();
  std::printf("[ near ] near skin %.3g d: %llu markings, %llu builds in 1500 substeps\n",
              some->contactModel().listNearSkin / s.particleDiameter,
              static_cast<unsigned long long>(stats.listNearMarkings),
              static_cast<unsigned long long>(stats.listBuilds));
  EXPECT_GT(stats.listNearMarkings, 3 * stats.listBuilds) << "markings between builds";
  EXPECT_GT(stats.contacts, 30u);
  EXPECT_EQ(some->readStateHash(), every->readStateHash());
}

// The pair counts of the damping are taken again only for granules whose contact slots changed
// (common/contact_pairs.glsl), and for all after the CPU changed the bodies. They and every bit of
// the state are those of taking them for every granule in every substep: through the pile's
// fall, a block added onto it, a snapshot restored, and with sleep, as the pile falls asleep
// after the restore.
TEST(Determinism, PairCountsTakenWhereTheSlotsChangedAreThoseOfEverySubstep) {
  for (const bool sleep : {false, true}) {
    WorldSettings s = testing::smallSettings();
    s.sleep.enabled = sleep;
    testing::TestWorld where(s), every(s);
    testing::countEveryPair(*every);
    for (testing::TestWorld* w : {&where, &every}) {
      buildPile(**w);
      (*w)->substep(300);
    }
    EXPECT_EQ(where->readStateHash(), every->readStateHash()) << "the fall, sleep " << sleep;
    const WorldSnapshot snapshot = where->readSnapshot();
    for (testing::TestWorld* w : {&where, &every}) {
      (*w)->addGranules(
          GranuleBlock{.center = {0, 0.12f, 0}, .countX = 3, .countY = 1, .countZ = 3, .seed = 9});
      (*w)->substep(300);
    }
    EXPECT_EQ(where->readStateHash(), every->readStateHash()) << "the block, sleep " << sleep;
    EXPECT_GT(where->readStats().contacts, 30u);
    for (testing::TestWorld* w : {&where, &every}) {
      (*w)->restoreSnapshot(snapshot);
      if (sleep) {
        w->simulate(1.2);
      } else {
        (*w)->substep(300);
      }
    }
    EXPECT_EQ(where->readStateHash(), every->readStateHash()) << "the restore, sleep " << sleep;
    if (sleep) {
      EXPECT_GT(where->readStats().granulesAsleep, 0u);
    }
  }
}

// The contacts pass leaves a particle whose partners are not all in its list (more than the list
// holds, or with sleep a list that a build passed over) to a pass that searches the grid
// (contacts.comp, SEARCHING). Every bit of the state is that of leaving every particle to it:
// through a fall with lists so roomy that they overflow, and with sleep, a block dropped onto the
// sleeping pile, which touches sleepers whose lists the builds of its fall passed over.
TEST(Determinism, ContactsLeftToTheGridSearchAreThoseOfEveryParticleSearched) {
  for (const bool sleep : {false, true}) {
    WorldSettings s = sleep ? testing::sleepingPileSettings() : testing::smallSettings();
    if (!sleep) s.listSkin = s.particleDiameter;
    testing::TestWorld some(s), every(s);
    testing::searchEveryParticle(*every);
    for (testing::TestWorld* w : {&some, &every}) {
      buildPile(**w);
      if (sleep) {
        w->simulate(1.5);
        (*w)->addGranules(GranuleBlock{
            .center = {0, 0.16f, 0}, .countX = 2, .countY = 1, .countZ = 2, .seed = 5});
      }
    }
    if (sleep) {
      EXPECT_GT(some->readStats().granulesAsleep, 80u);
    }
    std::uint64_t left = 0;
    for (int substep = 0; substep < 2000; ++substep) {
      some->substep(1);
      every->substep(1);
      left += testing::particlesLeftToSearch(*some);
    }
    std::printf("[ search ] sleep %d: %llu particles left to the grid search in 2000 substeps\n",
                int(sleep), static_cast<unsigned long long>(left));
    EXPECT_GT(left, 0u) << "the search pass is not exercised, sleep " << sleep;
    EXPECT_EQ(some->readStateHash(), every->readStateHash()) << "sleep " << sleep;
    EXPECT_GT(some->readStats().contacts, 30u);
  }
}

// Without sleep the contacts pass leaves the particles that the last list build found near a
// collider to a pass with the collider code (contacts.comp, COLLIDERS_PASS): the others touch no
// collider until the next build, and a collider the CPU adds or changes asks for one. Every bit
// of the state is that of every particle running the collider code (the grid search has it):
// through the fall into the box, and with a ceiling then set down onto the settled pile, whose
// top granules were near no collider.
TEST(Determinism, ParticlesLeftToTheColliderPassAreThoseOfEveryParticleWithItsCode) {
  testing::TestWorld some, every;
  testing::searchEveryParticle(*every);
  for (testing::TestWorld* w : {&some, &every}) buildPile(**w);
  std::uint64_t left = 0;
  for (int substep = 0; substep < 1500; ++substep) {
    some->substep(1);
    every->substep(1);
    left += testing::particlesLeftToColliders(*some);
  }
  const std::uint64_t particles = some->particleCount();
  std::printf("[ colliders ] %.1f%% of the particles run the collider code in 1500 substeps\n",
              100.0 * double(left) / double(1500 * particles));
  EXPECT_GT(left, 0u) << "the collider pass is not exercised";
  EXPECT_LT(left, 1500 * particles / 2) << "most particles should be far from every collider";
  EXPECT_EQ(some->readStateHash(), every->readStateHash()) << "the fall";

  float top = 0.0f;
  for (const ParticleState& p : some->readParticles()) top = std::max(top, p.position.y);
  const float d = some->settings().particleDiameter;
  const float ceiling = top + 0.4f * d;  // a tenth of d into the highest particle
  ColliderId ceilingId;
  for (testing::TestWorld* w : {&some, &every}) {
    ceilingId = (*w)->addCollider(Plane{.normal = {0, -1, 0}, .offset = -ceiling});
    (*w)->substep(1);
  }
  std::size_t touching = 0;
  for (const ContactRecord& c : some->readContacts()) touching += c.collider == ceilingId;
  EXPECT_GT(touching, 0u) << "the ceiling touches no granule";
  for (testing::TestWorld* w : {&some, &every}) (*w)->substep(200);
  EXPECT_EQ(some->readStateHash(), every->readStateHash()) << "the ceiling";
}

// The contacts pass every particle runs loads one group of contact slots and leaves a particle
// with more in use to a pass that loads more (contacts.comp, LOADED_SLOTS): without sleep the
// collider pass, away from any collider too, which loads two groups and leaves a particle with
// more still to the search's; with sleep the search's. A sphere with its twelve neighbours of a
// close packing, each of which touches five, pressed together and turning: every bit is that of
// every particle running with every slot (the grid search's pass).
class MoreSlotsThanLoaded : public ::testing::TestWithParam<bool> {};

TEST_P(MoreSlotsThanLoaded, KeepTheirBits) {
  const bool sleep = GetParam();
  WorldSettings settings = testing::smallSettings();
  settings.sleep.enabled = sleep;
  testing::TestWorld some(settings), every(settings);
  testing::searchEveryParticle(*every);
  const float d = some->settings().particleDiameter;
  const float a = 0.97f * d / std::sqrt(2.0f);  // a little closer than touching
  const Vec3 centre{0.0f, 0.5f, 0.0f};
  for (testing::TestWorld* w : {&some, &every}) {
    w->addSphere(centre);
    for (int axis = 0; axis < 3; ++axis) {
      for (float s : {-a, a}) {
        for (float t : {-a, a}) {
          float r[3] = {0.0f, 0.0f, 0.0f};
          r[axis] = s;
          r[(axis + 1) % 3] = t;
          // Closing in on the centre and going round the vertical.
          const Vec3 v{-0.3f * r[0] / d - 0.5f * r[2] / d, -0.3f * r[1] / d,
                       -0.3f * r[2] / d + 0.5f * r[0] / d};
          w->addSphere({centre.x + r[0], centre.y + r[1], centre.z + r[2]}, v);
        }
      }
    }
  }
  std::uint32_t left = 0, searched = 0;
  for (int substep = 0; substep < 60; ++substep) {
    some->substep(1);
    every->substep(1);
    left = std::max(left, sleep ? testing::particlesLeftToSearch(*some)
                                : testing::particlesLeftToColliders(*some));
    searched = std::max(searched, testing::particlesLeftToSearch(*some));
  }
  EXPECT_GT(left, 0u) << "no particle had more slots in use than the contacts pass loads";
  // The centre's twelve slots are more than the collider pass loads too.
  EXPECT_GT(searched, 0u) << "no particle reached the search's pass";
  EXPECT_EQ(some->readStateHash(), every->readStateHash());
}

INSTANTIATE_TEST_SUITE_P(Determinism, MoreSlotsThanLoaded, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param) {
                           return param.param ? "Sleep" : "NoSleep";
                         });

TEST(Determinism, KernelProfilingChangesNoBit) {
  // A benchmark times a span without the timer queries and profiles the next: switching them
  // on and off between steps must not touch the state, and the times follow the switch.
  testing::TestWorld plain, profiled;
  buildPile(*plain);
  buildPile(*profiled);
  plain->substep(100);
  profiled->substep(50);
  profiled->setProfileKernels(true);
  profiled->substep(30);
  const std::vector<KernelTime> times = profiled->kernelTimes();
  const auto contacts = std::find_if(times.begin(), times.end(),
                                     [](const KernelTime& t) { return t.name == "contacts"; });
  ASSERT_NE(contacts, times.end());
  EXPECT_EQ(contacts->dispatches, 30u);
  EXPECT_GT(contacts->milliseconds, 0.0);
  profiled->setProfileKernels(false);
  profiled->substep(20);
  EXPECT_TRUE(profiled->kernelTimes().empty());
  EXPECT_TRUE(identical(plain->readBodies(), profiled->readBodies()));
  EXPECT_EQ(plain->readStateHash(), profiled->readStateHash());
}

TEST(Determinism, ADifferentSeedGivesADifferentPile) {
  testing::TestWorld a, b;
  buildPile(*a);
  b->addCollider(Plane{});
  b->addCollider(Box{.center = {0, 0.3f, 0}, .halfExtents = {0.1f, 0.3f, 0.1f}, .inside = true});
  b->addGranules(
      GranuleBlock{.center = {0, 0.12f, 0}, .countX = 4, .countY = 6, .countZ = 4, .seed = 12});
  a->substep(200);
  b->substep(200);
  EXPECT_FALSE(identical(a->readBodies(), b->readBodies()));
}

}  // namespace
}  // namespace sandphys
