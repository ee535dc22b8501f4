// ContactLaw::HertzMindlin against closed forms and known results: static friction holds a
// granule on a slope below atan μ and lets it slide at g (sin θ - μ cos θ) above; friction at
// the contact point lets a sphere roll freely and keeps angular momentum in a glancing impact;
// the set restitution is what a sphere, a face-down granule and a sampled box get; a block of
// granules on a tilted floor does not creep; both sides of a contact get exactly opposite
// forces; a moving collider drags what rests on it; contacts beyond the slots are counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::TestWorld;

constexpr double kPi = std::numbers::pi;

// In double: the drift and spin the tests bound are far below a float's step at the pile's size.
double norm(Vec3 v) {
  return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
}

// Rotation by `angle` (rad) about the unit `axis`.
Quat aboutAxis(Vec3 axis, double angle) {
  const double s = std::sin(0.5 * angle);
  return {float(std::cos(0.5 * angle)), float(axis.x * s), float(axis.y * s), float(axis.z * s)};
}

// Orientation that turns the template's vertex (1, 1, 1)/√3 to +y: the opposite face lies flat.
Quat faceDown() {
  return aboutAxis({float(-1.0 / std::sqrt(2.0)), 0.0f, float(1.0 / std::sqrt(2.0))},
                   std::acos(1.0 / std::sqrt(3.0)));
}

// Height of a face-down granule's centre above the surface it rests on: the particle radius
// plus the distance from the centre to the plane of the face's particle centres.
float restingHeight(float d) {
  return 0.5f * d + d * std::sqrt(6.0f) / 12.0f;
}

WorldSettings settingsWith(float friction, Vec3 gravity = {0.0f, -9.81f, 0.0f}) {
  WorldSettings s = testing::smallSettings();
  s.material.friction = friction;
  s.gravity = gravity;
  return s;
}

// A plane through the origin tilted by θ about z: its surface rises along +x, so downhill is
// `downhill(θ)`.
Plane slope(double theta, float friction) {
  return Plane{.normal = {float(-std::sin(theta)), float(std::cos(theta)), 0.0f},
               .offset = 0.0f,
               .material = {.friction = friction, .restitution = 0.5f}};
}
Vec3 downhill(double theta) {
  return {float(-std::cos(theta)), float(-std::sin(theta)), 0.0f};
}

// A face-down granule resting on `slope(theta)`, just touching it, at distance `along` from the
// origin along the slope.
BodyId granuleOnSlope(TestWorld& w, double theta, float along = 0.0f) {
  const float d = w->settings().particleDiameter;
  const Quat tilt = aboutAxis({0.0f, 0.0f, 1.0f}, theta);
  const Vec3 normal{float(-std::sin(theta)), float(std::cos(theta)), 0.0f};
  const Vec3 position = (restingHeight(d) + 1e-5f) * normal + along * downhill(theta);
  return w.addGranule(position, tilt * faceDown());
}

TEST(ContactMechanics, GranuleRestsOnASlopeBelowAtanMu) {
  // θ = 15° < atan 0.5 = 26.6°, and below the 22° at which a face-down granule would tip.
  const double theta = 15.0 * kPi / 180.0;
  TestWorld w(settingsWith(0.5f));
  w->addCollider(slope(theta, 0.5f));
  const BodyId g = granuleOnSlope(w, theta);
  w.simulate(0.3);  // lands and loads its springs
  const BodyState before = w->readBody(g);
  w.simulate(2.0);
  const BodyState after = w->readBody(g);
  const float d = w->settings().particleDiameter;
  const double drift = norm(after.position - before.position);
  std::printf("granule on a 15 deg slope, mu 0.5: drift over 2 s %.3g d, speed %.3g m/s\n",
              drift / d, norm(after.velocity));
  EXPECT_LT(drift, 0.01 * d);
}

TEST(ContactMechanics, GranuleSlidesAboveAtanMuAtTheCoulombAcceleration) {
  // μ = 0.2 (atan 11.3°) on 20°: sliding, and the contact force's tilt from the normal (atan μ)
  // stays inside what a face-down granule can take without tipping.
  const double theta = 20.0 * kPi / 180.0;
  const float mu = 0.2f;
  TestWorld w(settingsWith(mu));
  w->addCollider(slope(theta, mu));
  const BodyId g = granuleOnSlope(w, theta, -0.5f);
  w.simulate(0.1);  // past the landing
  const BodyState a = w->readBody(g);
  const double seconds = 0.3;
  w.simulate(seconds);
  const BodyState b = w->readBody(g);
  const double g0 = 9.81;
  const double expected = g0 * (std::sin(theta) - mu * std::cos(theta));
  const double measured =
      (dot(b.velocity, downhill(theta)) - dot(a.velocity, downhill(theta))) / seconds;
  std::printf("granule on a 20 deg slope, mu 0.2: acceleration %.4f m/s^2, closed form %.4f\n",
              measured, expected);
  EXPECT_NEAR(measured, expected, 0.05 * expected);
}

// A sphere settled 0.1 s on a floor, then set rolling without slipping along +x at v: v = ω ×
// (centre - contact), ω about -z, the rolling radius the centre's height. Returns the body and
// its state at rest.
std::pair<BodyId, BodyState> rollingSphere(TestWorld& w, float v) {
  w.addFloor(0.0f, {.friction = 0.5f, .restitution = 0.5f});
  const float d = w->settings().particleDiameter;
  const BodyId b = w->addBody(makeParticleTemplate({{0, 0, 0}}, d, w->settings().material.density),
                              {.position = {0.0f, 0.5f * d, 0.0f}});
  w.simulate(0.1);
  const BodyState rest = w->readBody(b);
  w->setBodyState(b, {rest.position, rest.orientation, {v, 0, 0}, {0, 0, -v / rest.position.y}});
  return {b, rest};
}

TEST(ContactMechanics, SphereRollingWithoutSlippingIsNotSlowed) {
  const float v = 0.5f;
  TestWorld w(settingsWith(0.5f));
  const BodyId b = rollingSphere(w, v).first;
  w.simulate(0.5);
  const BodyState rolled = w->readBody(b);
  std::printf("rolling sphere: speed %.5f m/s after 0.5 s (started %.5f), spin %.3f rad/s\n",
              rolled.velocity.x, v, rolled.angularVelocity.z);
  EXPECT_NEAR(rolled.velocity.x, v, 0.01 * v);
  // The paper's friction acts at the centre and only brakes: the same sphere slides to a stop.
  WorldSettings paper = settingsWith(0.5f);
  paper.contactLaw = ContactLaw::PaperViscous;
  TestWorld p(paper);
  const BodyId pb = rollingSphere(p, v).first;
  p.simulate(0.5);
  EXPECT_LT(p->readBody(pb).velocity.x, 0.5f * v);
}

// Rolling friction against a floor: a couple mu_r R F_n with R = d/2 and F_n = m g, against a
// sphere rolling without slipping (I = 2/5 m R² about its centre, 7/5 m R² about the contact)
// slows it at (5/7) mu_r g until it stops; then the rolling spring holds it where it stopped.
TEST(ContactMechanics, RollingFrictionSlowsARollingSphereAtFiveSeventhsMuRG) {
  WorldSettings settings = settingsWith(0.5f);
  settings.material.rollingFriction = 0.1f;
  TestWorld w(settings);
  const float d = w->settings().particleDiameter;
  const float v = 0.5f;
  const auto [b, rest] = rollingSphere(w, v);
  const double deceleration = 5.0 / 7.0 * settings.material.rollingFriction * 9.81;
  const double seconds = 0.4;
  w.simulate(seconds);
  const BodyState rolled = w->readBody(b);
  const double expected = v - deceleration * seconds;
  std::printf("rolling friction 0.1: speed %.5f m/s after %.1f s, closed form %.5f\n",
              rolled.velocity.x, seconds, expected);
  EXPECT_NEAR(rolled.velocity.x, expected, 0.01 * v);
  EXPECT_NEAR(rolled.angularVelocity.z * rest.position.y, -rolled.velocity.x, 0.01 * v)
      << "no longer rolling without slipping";
  // Stopped at v / deceleration = 0.73 s; then at rest for good.
  w.simulate(0.5);
  const BodyState stopped = w->readBody(b);
  w.simulate(0.5);
  const BodyState later = w->readBody(b);
  std::printf(
      "stopped at x = %.6f m (closed form %.6f), %.3g m/s; 0.5 s later %.3g m/s, moved "
      "%.3g m\n",
      stopped.position.x - rest.position.x, 0.5 * v * v / deceleration, stopped.velocity.x,
      later.velocity.x, later.position.x - stopped.position.x);
  EXPECT_NEAR(stopped.position.x - rest.position.x, 0.5 * v * v / deceleration, 0.01 * d);
  EXPECT_LT(std::abs(later.velocity.x), 1e-4f);
  EXPECT_LT(std::abs(later.position.x - stopped.position.x), 1e-4f * d);
}

// Rolling friction's static part: a sphere of radius R at rest on a slope, friction enough to
// keep it from sliding, is held by the couple mu_r R F_n as long as the weight's torque about the
// contact, m g sin(theta) R, is below it: tan(theta) < mu_r. Above, it rolls down at
// (5/7) g (sin(theta) - mu_r cos(theta)) (I = 2/5 m R², and a rolling couple mu_r R m g cos).
// A couple without a spring (or a stateless one that vanishes at rest) lets the held sphere creep.
// The contact World::readContacts lists carries the couple: held, it balances the friction's
// torque about the centre, m g sin(theta) R; rolling, it is at its cap mu_r R F_n.
TEST(ContactMechanics, RollingFrictionHoldsASphereOnASlopeBelowAtanMuR) {
  constexpr float kMuR = 0.1f;
  std::vector<ContactRecord> contacts;
  auto onSlope = [&](double theta, BodyState& before, BodyState& after) {
    WorldSettings settings = settingsWith(0.5f);
    settings.material.rollingFriction = kMuR;
    TestWorld w(settings);
    w->addCollider(slope(theta, 0.5f));
    const float d = w->settings().particleDiameter;
    const Vec3 normal{float(-std::sin(theta)), float(std::cos(theta)), 0.0f};
    const BodyId b =
        w->addBody(makeParticleTemplate({{0, 0, 0}}, d, w->settings().material.density),
                   {.position = (0.5f * d + 1e-5f) * normal});
    w.simulate(0.2);  // lands and loads its springs
    before = w->readBody(b);
    w.simulate(0.5);
    after = w->readBody(b);
    contacts = w->readContacts();
    return double(d);
  };
  // The listed contact's couple and the friction's torque about the sphere's centre `centre`.
  auto couples = [&](Vec3 centre) {
    EXPECT_EQ(contacts.size(), 1u);
    const ContactRecord& c = contacts.at(0);
    return std::pair{c.rollingTorque, cross(c.point - centre, c.tangentialForce)};
  };
  const double g0 = 9.81;
  const double held = std::atan(0.8 * kMuR);
  BodyState a, b;
  const double d = onSlope(held, a, b);
  const double drift = dot(b.position - a.position, downhill(held));
  std::printf("sphere on a slope of tan 0.8 mu_r: drift over 0.5 s %.3g d, spin %.3g rad/s\n",
              drift / d, double(norm(b.angularVelocity)));
  EXPECT_LT(std::abs(drift), 1e-4 * d);
  EXPECT_LT(norm(b.angularVelocity), 1e-3f);
  const double mass = settingsWith(0.5f).material.density * kPi / 6.0 * d * d * d;
  const auto [heldCouple, heldFriction] = couples(b.position);
  std::printf("held: rolling couple %.4g N m, friction's torque %.4g, m g sin R %.4g\n",
              double(norm(heldCouple)), double(norm(heldFriction)),
              mass * g0 * std::sin(held) * 0.5 * d);
  EXPECT_NEAR(norm(heldCouple), mass * g0 * std::sin(held) * 0.5 * d,
              0.01 * mass * g0 * std::sin(held) * 0.5 * d);
  EXPECT_LT(norm(heldCouple + heldFriction), 1e-3 * norm(heldCouple));

  const double rolls = std::atan(2.0 * kMuR);
  onSlope(rolls, a, b);
  const double expected = 5.0 / 7.0 * g0 * (std::sin(rolls) - kMuR * std::cos(rolls));
  const double measured =
      (dot(b.velocity, downhill(rolls)) - dot(a.velocity, downhill(rolls))) / 0.5;
  std::printf("sphere on a slope of tan 2 mu_r: acceleration %.4f m/s^2, closed form %.4f\n",
              measured, expected);
  EXPECT_NEAR(measured, expected, 0.02 * expected);
  const ContactRecord& rolling = contacts.at(0);
  EXPECT_NEAR(norm(rolling.rollingTorque), kMuR * 0.5 * d * rolling.normalForce,
              1e-3 * kMuR * 0.5 * d * rolling.normalForce);
}

// A granule hanging by the two particles of its top edge on two fixed spheres, its centre below
// the line through the two contacts, tilted by 0.1 rad about that line and let go: it swings
// like a pendulum, its particles rolling on the spheres. Rolling without slipping, no contact
// force does work, so without rolling friction nothing stops the swing: a rattler of the settled
// box pile swung so, and kept its neighbours awake. Returns the largest spin, rad/s, over the
// first 0.3 s and over the last 0.3 s of `seconds`.
std::pair<double, double> hangingSwing(float rollingFriction, double seconds) {
  WorldSettings settings = settingsWith(0.5f);
  settings.material.rollingFriction = rollingFriction;
  TestWorld w(settings);
  const float d = w->settings().particleDiameter;
  const float density = w->settings().material.density;
  // tetrahedronTemplate's corners are (±h, ±h, ±h): the top edge runs from (h, h, h) to
  // (-h, h, -h), along `along`. Each of its particles rests on a sphere beyond the edge's end,
  // 30° below it, so the line through the contacts is at y = h - d/4 above the centre.
  const float h = d / (2.0f * std::numbers::sqrt2_v<float>);
  const Vec3 along = normalized(Vec3{1.0f, 0.0f, 1.0f});
  const Vec3 centre{0.0f, 0.5f, 0.0f};
  for (const float side : {1.0f, -1.0f}) {
    const Vec3 top = centre + Vec3{side * h, h, side * h};
    w->addBody(makeParticleTemplate({{0, 0, 0}}, d, density),
               {.position = top + (side * 0.8660254f * d) * along - Vec3{0.0f, 0.5f * d, 0.0f},
                .motion = Motion::Static});
  }
  const Vec3 pivot = centre + Vec3{0.0f, h - 0.25f * d, 0.0f};
  const Quat tilt = fromAxisAngle(along, 0.1f);
  const BodyId g =
      w->addBody(tetrahedronTemplate(d, density),
                 {.position = pivot + rotate(tilt, centre - pivot), .orientation = tilt});
  double first = 0.0, last = 0.0;
  constexpr double kSample = 0.01;
  for (double t = kSample; t <= seconds + 1e-9; t += kSample) {
    w.simulate(kSample);
    const double spin = norm(w->readBody(g).angularVelocity);
    if (t <= 0.3) first = std::max(first, spin);
    if (t > seconds - 0.3) last = std::max(last, spin);
  }
  std::printf(
      "hanging granule, rolling friction %g: largest spin %.4f rad/s in the first 0.3 s, "
      "%.4f in the last 0.3 s of %.1f s; centre at y = %.4f m\n",
      double(rollingFriction), first, last, seconds, double(w->readBody(g).position.y));
  EXPECT_GT(w->readBody(g).position.y, 0.4f) << "it fell off its supports";
  return {first, last};
}

TEST(ContactMechanics, AGranuleSwingingOnTwoContactsStopsOnlyWithRollingFriction) {
  const auto [freeFirst, freeLast] = hangingSwing(0.0f, 1.0);
  EXPECT_GT(freeFirst, 0.5) << "it did not swing";
  EXPECT_GT(freeLast, 0.8 * freeFirst) << "something else damps the swing";
  const auto [rollingFirst, rollingLast] = hangingSwing(0.02f, 1.0);
  EXPECT_LT(rollingLast, 0.05 * freeFirst);
}

// Angular momentum about the origin of single-particle bodies: m x × v + I ω, I = m d²/10.
Vec3 angularMomentum(const BodyState& s, double mass, double d) {
  const double inertia = 0.1 * mass * d * d;
  const Vec3 orbital = cross(s.position, s.velocity);
  return {float(mass * orbital.x + inertia * s.angularVelocity.x),
          float(mass * orbital.y + inertia * s.angularVelocity.y),
          float(mass * orbital.z + inertia * s.angularVelocity.z)};
}

TEST(ContactMechanics, GlancingFrictionalCollisionKeepsAngularMomentum) {
  TestWorld w(settingsWith(0.5f, {0, 0, 0}));
  const float d = w->settings().particleDiameter;
  const double mass = w->contactModel().particleMass;
  // Impact parameter d/2: the contact's normal is 30° off the line of motion, so friction acts.
  const float v = 0.5f;
  const BodyId a = w.addSphere({-0.6f * d, 0.25f * d, 0.0f}, {v, 0.0f, 0.0f});
  const BodyId b = w.addSphere({0.6f * d, -0.25f * d, 0.0f}, {-v, 0.0f, 0.0f});
  auto total = [&] {
    return angularMomentum(w->readBody(a), mass, d) + angularMomentum(w->readBody(b), mass, d);
  };
  const Vec3 before = total();
  w.simulate(0.05);  // through the contact and apart
  const Vec3 after = total();
  const double spin = norm(w->readBody(a).angularVelocity);
  std::printf("glancing collision: L %.6g -> %.6g kg m^2/s, spin %.3f rad/s\n", before.z, after.z,
              spin);
  EXPECT_LT(norm(after - before), 0.01 * norm(before));
  EXPECT_GT(spin, 1.0) << "friction at the contact point spins the spheres";
}

// Rolling friction's couples on the two sides of a contact are exactly opposite: two spheres
// meeting head-on with spins across the normal keep their total angular momentum, and end with
// less relative rolling than without rolling friction.
TEST(ContactMechanics, RollingFrictionKeepsAngularMomentumAndTakesRelativeRolling) {
  struct Outcome {
    Vec3 before, after;
    float rolling;  // |relative spin across the normal (x)| after, rad/s
  };
  auto collide = [](float rollingFriction) {
    WorldSettings settings = settingsWith(0.5f, {0, 0, 0});
    settings.material.rollingFriction = rollingFriction;
    TestWorld w(settings);
    const float d = w->settings().particleDiameter;
    const double mass = w->contactModel().particleMass;
    const ParticleTemplate sphere =
        makeParticleTemplate({{0, 0, 0}}, d, w->settings().material.density);
    const BodyId a = w->addBody(sphere, {.position = {-0.51f * d, 0.0f, 0.0f},
                                         .velocity = {0.2f, 0.0f, 0.0f},
                                         .angularVelocity = {2.0f, 30.0f, -20.0f}});
    const BodyId b = w->addBody(sphere, {.position = {0.51f * d, 0.0f, 0.0f},
                                         .velocity = {-0.2f, 0.0f, 0.0f},
                                         .angularVelocity = {-1.0f, -10.0f, 5.0f}});
    auto total = [&] {
      return angularMomentum(w->readBody(a), mass, d) + angularMomentum(w->readBody(b), mass, d);
    };
    Outcome o;
    o.before = total();
    w.simulate(0.02);  // through the contact and apart
    o.after = total();
    const Vec3 relative = w->readBody(a).angularVelocity - w->readBody(b).angularVelocity;
    o.rolling = std::hypot(relative.y, relative.z);
    return o;
  };
  const Outcome with = collide(0.3f);
  const Outcome without = collide(0.0f);
  std::printf(
      "head-on, spinning: L (%.4g, %.4g, %.4g) -> (%.4g, %.4g, %.4g); relative rolling "
      "after %.4f rad/s, %.4f without rolling friction\n",
      with.before.x, with.before.y, with.before.z, with.after.x, with.after.y, with.after.z,
      with.rolling, without.rolling);
  EXPECT_LT(norm(with.after - with.before), 1e-3 * norm(with.before));
  EXPECT_LT(with.rolling, 0.99f * without.rolling) << "the couple did not act";
}

TEST(ContactMechanics, BothSidesOfAContactGetExactlyOppositeForces) {
  // Two spinning spheres in a glancing frictional contact: every substep, the force on one is the
  // other's negated, bit for bit (each has this one contact only, so its sum is the contact).
  TestWorld w(settingsWith(0.5f, {0, 0, 0}));
  const float d = w->settings().particleDiameter;
  w->addBody(makeParticleTemplate({{0, 0, 0}}, d, w->settings().material.density),
             {.position = {-0.55f * d, 0.2f * d, 0.01f * d},
              .velocity = {0.3f, 0.05f, -0.02f},
              .angularVelocity = {3.0f, -7.0f, 11.0f}});
  w->addBody(makeParticleTemplate({{0, 0, 0}}, d, w->settings().material.density),
             {.position = {0.55f * d, -0.2f * d, 0.0f},
              .velocity = {-0.3f, 0.0f, 0.04f},
              .angularVelocity = {-5.0f, 2.0f, 1.0f}});
  int touching = 0;
  for (int i = 0; i < 400; ++i) {
    w->substep(1);
    const auto p = w->readParticles();
    if (p[0].force.x == 0.0f && p[0].force.y == 0.0f) continue;
    ++touching;
    ASSERT_EQ(p[0].force.x, -p[1].force.x) << "substep " << i;
    ASSERT_EQ(p[0].force.y, -p[1].force.y) << "substep " << i;
    ASSERT_EQ(p[0].force.z, -p[1].force.z) << "substep " << i;
  }
  EXPECT_GT(touching, 10);
}

// Velocity along `normal` after a body launched into a plane at `speed` leaves it (no gravity),
// over the velocity it came in with: the restitution it got.
double bounce(TestWorld& w, BodyId body, float speed) {
  const BodyState in = w->readBody(body);
  w.simulate(0.08);
  const BodyState out = w->readBody(body);
  EXPECT_LT(in.velocity.y, 0.0f);
  return out.velocity.y / speed;
}

TEST(ContactMechanics, RestitutionIsTheSetOneForASphereAGranuleAndASampledBox) {
  const float e = 0.5f;
  const float v = 0.5f;
  WorldSettings s = settingsWith(0.5f, {0, 0, 0});
  s.material.restitution = e;
  const SurfaceMaterial floor{.friction = 0.5f, .restitution = e};
  const float d = s.particleDiameter;
  {
    TestWorld w(s);
    w.addFloor(0.0f, floor);
    const BodyId b = w.addSphere({0.0f, 0.5f * d + 1e-4f, 0.0f}, {0.0f, -v, 0.0f});
    const double got = bounce(w, b, v);
    std::printf("restitution: sphere %.4f (set %.2f)\n", got, e);
    EXPECT_NEAR(got, e, 0.05 * e);
  }
  {
    TestWorld w(s);
    w.addFloor(0.0f, floor);
    const BodyId b =
        w.addGranule({0.0f, restingHeight(d) + 1e-4f, 0.0f}, faceDown(), {0.0f, -v, 0.0f});
    const double got = bounce(w, b, v);
    std::printf("restitution: face-down granule %.4f (set %.2f)\n", got, e);
    EXPECT_NEAR(got, e, 0.05 * e);
  }
  {
    TestWorld w(s);
    w.addFloor(0.0f, floor);
    // A closed box of 8 x 3 x 6 d: its bottom face is a lattice of particles in one plane.
    const SampledMesh box =
        sampleMesh(boxMesh({-4.0f * d, -1.5f * d, -3.0f * d}, {4.0f * d, 1.5f * d, 3.0f * d}), d,
                   {.density = 1000.0f});
    float lowest = 0.0f;
    for (const Vec3& c : box.centres) lowest = std::min(lowest, c.y);
    const Vec3 com{float(box.massProperties.centreOfMass[0]),
                   float(box.massProperties.centreOfMass[1]),
                   float(box.massProperties.centreOfMass[2])};
    const BodyId b =
        w->addBody(box.shape, {.position = {0.0f, com.y - lowest + 0.5f * d + 1e-4f, 0.0f},
                               .velocity = {0.0f, -v, 0.0f}});
    const double got = bounce(w, b, v);
    std::printf("restitution: sampled box of %zu particles %.4f (set %.2f)\n",
                box.shape.offsets.size(), got, e);
    EXPECT_NEAR(got, e, 0.05 * e);
  }
}

TEST(ContactMechanics, BlockOfGranulesOnATiltedFloorDoesNotCreep) {
  // A loose block of granules settles on a floor tilted by 10° (μ 0.5 everywhere) and then
  // stays where it settled. A low drop: a soft material and a low speed guard allow a long step.
  const double theta = 10.0 * kPi / 180.0;
  WorldSettings s = settingsWith(0.5f);
  s.material.youngsModulus = 2.0e6f;
  s.maxSpeed = 1.0f;
  TestWorld w(s);
  w->addCollider(slope(theta, 0.5f));
  const float d = s.particleDiameter;
  const Vec3 normal{float(-std::sin(theta)), float(std::cos(theta)), 0.0f};
  const BodyRange block = w->addGranules(
      {.center = 3.0f * d * normal, .countX = 4, .countY = 2, .countZ = 4, .seed = 3});
  auto centroid = [&] {
    Vec3 sum{};
    const auto bodies = w->readBodies();
    for (const BodyId id : block) sum = sum + bodies[id.index].position;
    return (1.0f / float(block.size())) * sum;
  };
  w.simulate(1.5);  // falls, piles up and settles
  const Vec3 before = centroid();
  w.simulate(1.0);
  const double drift = norm(centroid() - before);
  std::printf("block of %u granules on a 10 deg floor: centroid drift over 1 s %.3g d\n",
              block.size(), drift / d);
  EXPECT_LT(drift, 0.01 * d);
}

TEST(ContactMechanics, MovingColliderDragsWhatRestsOnIt) {
  // A conveyor: a floor whose surface moves at 0.2 m/s along x carries a granule resting on it
  // up to its own speed (the pose never changes; only the contacts see the motion).
  TestWorld w(settingsWith(0.5f));
  const float belt = 0.2f;
  w->addCollider(Plane{.normal = {0, 1, 0},
                       .offset = 0.0f,
                       .material = {.friction = 0.5f, .restitution = 0.5f},
                       .motion = {.velocity = {belt, 0.0f, 0.0f}}});
  const float d = w->settings().particleDiameter;
  const BodyId g = w.addGranule({0.0f, restingHeight(d) + 1e-5f, 0.0f}, faceDown());
  w.simulate(0.5);
  const BodyState s = w->readBody(g);
  std::printf("granule on a belt at %.2f m/s: %.4f m/s after 0.5 s\n", belt, s.velocity.x);
  EXPECT_NEAR(s.velocity.x, belt, 0.02 * belt);
}

TEST(ContactMechanics, MoveColliderDerivesTheVelocityFromThePoseChange) {
  TestWorld w(settingsWith(0.5f));
  const ColliderId id = w->addCollider(Box{.center = {0, 0, 0}, .halfExtents = {1, 1, 1}});
  const Quat turned = aboutAxis({0, 1, 0}, 0.1);
  w->moveCollider(id, Box{.center = {0.02f, 0, 0}, .halfExtents = {1, 1, 1}, .orientation = turned},
                  0.1f);
  const Box moved = std::get<Box>(w->colliders()[0]);
  EXPECT_NEAR(moved.motion.velocity.x, 0.2f, 1e-5f);
  EXPECT_NEAR(moved.motion.angularVelocity.y, 1.0f, 1e-4f);
  EXPECT_THROW(w->moveCollider(id, Box{}, 0.0f), InvalidArgument);
  EXPECT_THROW(w->moveCollider(ColliderId{5}, Box{}, 0.1f), InvalidId);
}

TEST(ContactMechanics, ContactsBeyondTheSlotsAreCounted) {
  // One sphere pressed by 14 others at once: 12 slots take the first contacts found and the rest
  // are counted, never silently dropped.
  TestWorld w(settingsWith(0.5f, {0, 0, 0}));
  const float d = w->settings().particleDiameter;
  w.addSphere({0, 0, 0});
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < 14; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / 14.0;
    const double r = std::sqrt(1.0 - y * y);
    const Vec3 dir{float(r * std::cos(golden * i)), float(y), float(r * std::sin(golden * i))};
    w.addSphere(0.95f * d * dir);
  }
  w->substep(1);
  const WorldStats stats = w->readStats();
  EXPECT_GE(stats.contactSlotOverflows, 2u);
  EXPECT_EQ(stats.penetrationClamps, 0u);
}

}  // namespace
}  // namespace sandphys
