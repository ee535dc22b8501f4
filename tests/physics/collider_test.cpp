// Every implicit collider holds a resting sphere at the Hertz overlap of the load it carries,
// pushing along the surface normal; and the contact list reports those contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "support/test_world.h"

namespace sandphys {
namespace {

struct Case {
  const char* name;
  Vec3 gravity;  // points into the surface
  Vec3 start;    // sphere centre, touching the surface
  Vec3 normal;   // expected contact normal (out of the surface)
  ColliderId (*add)(World&);
};

double norm(Vec3 v) {
  return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
}

class ColliderRest : public ::testing::TestWithParam<Case> {};

TEST_P(ColliderRest, SphereSettlesAtTheHertzOverlapOfItsWeight) {
  const Case& c = GetParam();
  WorldSettings s = testing::smallSettings();
  s.gravity = c.gravity;
  testing::TestWorld w(s);
  const ColliderId collider = c.add(*w);
  BodyId sphere = w.addSphere(c.start);
  w.simulate(0.25);
  const ContactModel& m = w->contactModel();
  const double load = m.particleMass * norm(c.gravity);
  const double expected = hertzRestingOverlap(load, m.stiffnessWall);
  auto contacts = w->readContacts();
  ASSERT_EQ(contacts.size(), 1u) << c.name;
  const ContactRecord& k = contacts[0];
  EXPECT_EQ(k.particleB, ContactRecord::kNone);
  EXPECT_EQ(k.collider, collider);
  EXPECT_NEAR(k.overlap, expected, 0.02 * expected) << c.name;
  EXPECT_NEAR(k.normalForce, load, 0.02 * load) << c.name;
  EXPECT_NEAR(k.normal.x, c.normal.x, 1e-3) << c.name;
  EXPECT_NEAR(k.normal.y, c.normal.y, 1e-3) << c.name;
  EXPECT_NEAR(k.normal.z, c.normal.z, 1e-3) << c.name;
  EXPECT_LT(norm(w->readBody(sphere).velocity), 1e-3) << c.name;
}

constexpr float r = 0.01f;  // particle radius of the default settings
const float kCos45 = std::sqrt(0.5f);

INSTANTIATE_TEST_SUITE_P(
    Colliders, ColliderRest,
    ::testing::Values(
        Case{"plane",
             {0, -9.81f, 0},
             {0, r, 0},
             {0, 1, 0},
             [](World& w) { return w.addCollider(Plane{}); }},
        Case{"tilted plane",
             {-9.81f * kCos45, -9.81f * kCos45, 0},
             {r * kCos45, r* kCos45, 0},
             {kCos45, kCos45, 0},
             [](World& w) {
               return w.addCollider(Plane{.normal = {1, 1, 0}, .offset = 0});
             }},
        Case{"box container wall",
             {9.81f, 0, 0},
             {0.1f - r, 0, 0},
             {-1, 0, 0},
             [](World& w) {
               return w.addCollider(Box{.halfExtents = {0.1f, 0.1f, 0.1f}, .inside = true});
             }},
        Case{"box obstacle top",
             {0, -9.81f, 0},
             {0.02f, 0.1f + r, 0.03f},
             {0, 1, 0},
             [](World& w) {
               return w.addCollider(Box{.halfExtents = {0.1f, 0.1f, 0.1f}, .inside = false});
             }},
        Case{"rotated box obstacle",
             {0, 0, -9.81f},
             {0, 0, 0.1f + r},
             {0, 0, 1},
             [](World& w) {
               // 90 degrees about y: the box's x face now faces +z.
               return w.addCollider(Box{.halfExtents = {0.1f, 0.3f, 0.4f},
                                        .orientation = {kCos45, 0, kCos45, 0},
                                        .inside = false});
             }},
        Case{"cylinder wall",
             {0, 0, 9.81f},
             {0, 0.5f, 0.2f - r},
             {0, 0, -1},
             [](World& w) { return w.addCollider(Cylinder{.radius = 0.2f, .height = 1.0f}); }},
        Case{"funnel wall",
             {9.81f * kCos45, -9.81f * kCos45, 0},
             {0.15f - r * kCos45, 0.1f + r* kCos45, 0},
             {-kCos45, kCos45, 0},
             // Outlet radius 0.05 at y = 0, 45 degrees: the cone passes through (0.15, 0.1).
             [](World& w) {
               return w.addCollider(
                   Funnel{.outletRadius = 0.05f, .halfAngle = 0.785398163f, .height = 0.5f});
             }}),
    [](const ::testing::TestParamInfo<Case>& param) {
      std::string name = param.param.name;
      for (char& ch : name) {
        if (ch == ' ') ch = '_';
      }
      return name;
    });

TEST(ContactList, GranuleOnAFloorCarriesItsWeightOnThreeContacts) {
  testing::TestWorld w;
  w.addFloor();
  const float d = w->settings().particleDiameter;
  // Face down (see closed_form_test.cpp).
  const double angle = std::acos(1.0 / std::sqrt(3.0));
  const double sn = std::sin(angle / 2.0) / std::sqrt(2.0);
  const BodyId granule = w.addGranule({0, 0.5f * d + d * std::sqrt(6.0f) / 12.0f, 0},
                                      {float(std::cos(angle / 2.0)), float(-sn), 0, float(sn)});
  w.simulate(0.3);
  auto contacts = w->readContacts();
  ASSERT_EQ(contacts.size(), 3u);
  double total = 0.0;
  for (const auto& c : contacts) {
    EXPECT_EQ(c.bodyA, granule);
    EXPECT_NEAR(c.normal.y, 1.0, 1e-4);
    total += c.normalForce;
  }
  const double weight = tetrahedronTemplate(d, w->settings().material.density).mass * 9.81;
  EXPECT_NEAR(total, weight, 0.01 * weight);
}

TEST(ContactList, ListsEachParticlePairOnceWithOppositeForces) {
  WorldSettings s = testing::smallSettings();
  s.gravity = {0, 0, 0};
  testing::TestWorld w(s);
  const float d = s.particleDiameter;
  w.addSphere({-0.45f * d, 0, 0});
  w.addSphere({0.45f * d, 0, 0});
  // The contacts the first substep applies, then the forces it applied.
  auto contacts = w->readContacts();
  w->substep(1);
  ASSERT_EQ(contacts.size(), 1u);
  const ContactRecord& c = contacts[0];
  EXPECT_EQ(c.particleA, 0u);
  EXPECT_EQ(c.particleB, 1u);
  EXPECT_NEAR(c.overlap, 0.1f * d, 1e-6);
  EXPECT_NEAR(c.normal.x, -1.0f, 1e-6);  // from B (right) to A (left)
  EXPECT_NEAR(c.point.x, 0.0f, 1e-6);
  auto particles = w->readParticles();
  EXPECT_FLOAT_EQ(particles[0].force.x, -particles[1].force.x);
  EXPECT_NEAR(particles[0].force.x, -c.normalForce, 1e-6 * c.normalForce);
  EXPECT_NEAR(c.normalForce, w->contactModel().stiffnessGrain * std::pow(0.1 * d, 1.5),
              1e-4 * c.normalForce);
}

}  // namespace
}  // namespace sandphys

namespace sandphys {
namespace {

// The stiffness check of a thin wall (ContactModel::peakOverlapWall): a granule at the speed
// guard that also spins at the guard's rim speed brings its leading particle to the wall at
// twice maxSpeed. At the largest maxSpeed the check accepts for the default material, such a
// granule thrown at a thin cylinder wall bounces off it; a maxSpeed a little above is refused.
TEST(ThinWall, AGranuleAtTheFastestTheGuardAllowsDoesNotPassThroughIt) {
  WorldSettings s = testing::smallSettings();
  s.gravity = {0, 0, 0};
  // The peak overlaps grow as speed^(4/5): the largest maxSpeed both checks (grain on grain,
  // grain on a thin wall) accept.
  const ContactModel defaults = ContactModel::fromSettings(s);
  const double d = s.particleDiameter;
  const float limit =
      s.maxSpeed *
      float(std::min(std::pow(kThinWallPassOverlap * d / defaults.peakOverlapWall, 1.25),
                     std::pow(kGrainPassOverlap * d / defaults.peakOverlapGrain, 1.25)));
  s.maxSpeed = 0.99f * limit;
  testing::TestWorld w(s);
  const float radius = 0.2f;
  w->addCollider(Cylinder{.base = {0, -0.5f, 0}, .radius = radius, .height = 1.0f});
  // Moving along +x and spinning about -z, so that the particles on its +y side move towards the
  // wall at the body's speed plus up to the rim speed (both at the guard).
  const float bounding = tetrahedronTemplate(s.particleDiameter, s.material.density).boundingRadius;
  const float v = 0.999f * s.maxSpeed;
  const BodyId g = w.addGranule({radius - 0.06f, 0, 0}, {}, {v, 0, 0}, {0, 0, -v / bounding});
  w.simulate(0.1);
  const BodyState after = w->readBody(g);
  const double distance = std::hypot(double(after.position.x), double(after.position.z));
  EXPECT_LT(distance, radius) << "the granule went through the wall";
  EXPECT_LT(after.velocity.x, 0.0f) << "it should have bounced back";

  WorldSettings faster = s;
  faster.maxSpeed = 1.02f * limit;
  EXPECT_THROW(ContactModel::fromSettings(faster), InvalidArgument);
}

}  // namespace
}  // namespace sandphys
