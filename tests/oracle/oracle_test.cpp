// The GPU step against the double-precision CPU oracle (cpu_oracle.h), under the default
// ContactLaw::HertzMindlin and under ContactLaw::PaperViscous: the same forces at one substep
// (and, under HertzMindlin, the same body velocities, spins and contact history after it), the
// same trajectories over 500 substeps, and proof that the comparison notices a model that is 10%
// off. The oracle starts from the GPU's state each time: the bodies and, under HertzMindlin, the
// contact history (World::readSnapshot). Every tolerance is stated next to its comparison with
// the error measured on llvmpipe when it was chosen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "oracle/cpu_oracle.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

using oracle::ContactHistoryMap;
using oracle::ContactKey;
using oracle::ContactPass;
using oracle::CpuOracle;
using oracle::OracleBody;
using oracle::OracleCollider;
using oracle::OracleContact;
using oracle::OracleModel;
using oracle::OracleParticle;
using oracle::toDouble;
using oracle::Vec3d;

constexpr double kEps = 0x1p-24;  // float unit round-off

// One unit in the last place of a float of magnitude x.
double ulp(double x) {
  return std::ldexp(1.0, std::ilogb(std::max(std::abs(x), 1e-30)) - 23);
}

// --- Scenes built twice in a line: in the World and as oracle input -------------------------

class OracleScene {
 public:
  OracleScene(std::uint32_t maxBodies, ContactLaw law, float rollingFriction = 0.0f)
      : m_world(settings(maxBodies, law, rollingFriction)) {}

  World& world() { return *m_world; }

  template <typename Collider>
  void addCollider(const Collider& collider) {
    m_world->addCollider(collider);
    m_colliders.push_back(OracleCollider::from(collider));
  }
  void addBody(const ParticleTemplate& shape, const BodyDesc& desc) {
    m_world->addBody(shape, desc);
    m_shapes.push_back(shape);
    m_motions.push_back(desc.motion);
  }
  void addGranules(const GranuleBlock& block) {
    const BodyRange range = m_world->addGranules(block);
    m_shapes.resize(m_shapes.size() + range.size(), granule());
    m_motions.resize(m_motions.size() + range.size(), Motion::Dynamic);
  }
  ParticleTemplate granule() {
    return tetrahedronTemplate(m_world->settings().particleDiameter,
                               m_world->settings().material.density);
  }
  ParticleTemplate sphere() {
    return makeParticleTemplate({{0, 0, 0}}, m_world->settings().particleDiameter,
                                m_world->settings().material.density);
  }

  /// An oracle holding the state the GPU holds now: bodies and contact history (a sync point).
  /// Its bodies are in the GPU's slot order, so that its particles and contact slots are numbered
  /// as the GPU's after a sort of the granules by place.
  CpuOracle oracle() {
    const WorldSnapshot snapshot = m_world->readSnapshot();
    const std::vector<BodyState> states = m_world->readBodies();
    std::vector<OracleBody> bodies;
    for (std::uint32_t slot = 0; slot < states.size(); ++slot) {
      const std::uint32_t id = snapshot.bodyIds.empty() ? slot : snapshot.bodyIds[slot];
      bodies.push_back(OracleBody::from(states[id], m_shapes[id], m_motions[id]));
    }
    return CpuOracle(OracleModel::fromWorld(*m_world), std::move(bodies), m_colliders,
                     oracle::historyFromSnapshot(snapshot));
  }

 private:
  static WorldSettings settings(std::uint32_t maxBodies, ContactLaw law, float rollingFriction) {
    WorldSettings s = testing::smallSettings(maxBodies);
    s.contactLaw = law;
    s.material.rollingFriction = rollingFriction;
    return s;
  }

  testing::TestWorld m_world;
  std::vector<OracleCollider> m_colliders;
  std::vector<ParticleTemplate> m_shapes;  // per body slot
  std::vector<Motion> m_motions;           // per body slot
};

double particleWeight(const World& w) {
  return w.contactModel().particleMass * std::abs(double(w.settings().gravity.y));
}

// The lowest point of a template's particle centres (y, m) when the body has orientation q.
double lowestOffset(const ParticleTemplate& shape, const Quat& q) {
  double lowest = 0.0;
  for (const Vec3& o : shape.offsets) {
    lowest = std::min(lowest, oracle::rotate(toDouble(q), toDouble(o)).y());
  }
  return lowest;
}

// 225 granules poured at 1 m/s into a narrow box container standing on a floor plane, then
// simulated `substeps` on the GPU: mid-impact, hundreds of contacts, every kind of contact state
// (new, approaching, separating, sticking, sliding; pairs, floor, walls, corners).
void buildPile(OracleScene& scene, std::uint32_t substeps) {
  scene.addCollider(Plane{});
  // The box reaches below the floor so that its bottom wall never doubles the floor.
  scene.addCollider(
      Box{.center = {0, 0.25f, 0}, .halfExtents = {0.125f, 0.3f, 0.125f}, .inside = true});
  scene.addGranules(GranuleBlock{.center = {0, 0.222f, 0},
                                 .countX = 5,
                                 .countY = 9,
                                 .countZ = 5,
                                 .velocity = {0, -1.0f, 0},
                                 .seed = 7});
  scene.world().substep(substeps);
}
// ~0.13 s: the column is still crashing in. The granules were sorted by place in substep 1001
// (kSortInterval); the substep after these is not a multiple of it plus one, so it sorts nothing
// and the slots compared before and after it hold the same bodies.
constexpr std::uint32_t kPileSubsteps = 1999;

// Separate collisions, far apart, each one kind of contact: sphere-sphere (oblique, so friction
// acts), granule-floor plane, granule-box container wall, granule-cylinder wall, granule-funnel,
// sphere-solid rotated box, granule-granule, sphere-kinematic sphere, sphere-static granule.
// Each starts a millimetre or a few from contact, so that the 500 substeps (~33 ms) cover the
// whole impact. And two that last: a granule resting face down on the floor (three contacts with
// one partner, so n = 3) that slides at 5 cm/s until friction stops it (μ g = 3.9 m/s²: ~13 ms)
// and then sticks; and a granule dropped onto a conveyor, a solid box whose surface moves
// (ColliderMotion: translating and turning) without its pose changing, which drags it along.
void buildCollisions(OracleScene& scene) {
  const float d = scene.world().settings().particleDiameter;
  const float gap = 1e-3f;  // m
  // A granule's particles reach d·√6/4 + d/2 from its centre.
  const float reach = d * (std::sqrt(6.0f) / 4.0f + 0.5f);
  const ParticleTemplate granule = scene.granule();
  const ParticleTemplate sphere = scene.sphere();
  // Some skew orientation (unit, so that lowestOffset can use it).
  const double tw = 0.9, tx = 0.3, ty = -0.2, tz = 0.25;
  const double tn = std::sqrt(tw * tw + tx * tx + ty * ty + tz * tz);
  const Quat tilted{float(tw / tn), float(tx / tn), float(ty / tn), float(tz / tn)};
  // Face down: the rotation taking the template's corner (1, 1, 1)/√3 to +y puts the opposite
  // face, three particles, at the bottom: q = normalise(1 + a·b, a × b).
  const double fw = 1.0 + 1.0 / std::sqrt(3.0), fx = -1.0 / std::sqrt(3.0),
               fz = 1.0 / std::sqrt(3.0);
  const double fn = std::sqrt(fw * fw + fx * fx + fz * fz);
  const Quat faceDown{float(fw / fn), float(fx / fn), 0.0f, float(fz / fn)};

  scene.addCollider(Plane{.material = {.friction = 0.4f, .restitution = 0.6f}});
  scene.addCollider(Box{.center = {0, 0.2f, 0},
                        .halfExtents = {0.3f, 0.3f, 0.3f},
                        .inside = true,
                        .material = {.friction = 0.3f, .restitution = 0.7f}});
  scene.addCollider(Cylinder{.base = {-0.15f, 0, -0.15f},
                             .radius = 0.06f,
                             .height = 0.4f,
                             .material = {.friction = 0.6f, .restitution = 0.4f}});
  scene.addCollider(Funnel{.outletCenter = {0.15f, 0.15f, -0.15f},
                           .outletRadius = 0.02f,
                           .halfAngle = 0.6f,
                           .height = 0.15f});
  scene.addCollider(Box{.center = {-0.15f, 0.1f, 0.15f},
                        .halfExtents = {0.03f, 0.03f, 0.03f},
                        .orientation = {0.966f, 0, 0.259f, 0},
                        .inside = false});
  // The conveyor: top face at y = 0.07 m, surface velocity (0.2, 0, 0) m/s at its centre plus
  // 1.5 rad/s about the vertical through it.
  const Vec3 conveyorTop{0.15f, 0.07f, 0.2f};
  scene.addCollider(Box{.center = {0.15f, 0.05f, 0.2f},
                        .halfExtents = {0.04f, 0.02f, 0.04f},
                        .inside = false,
                        .material = {.friction = 0.5f, .restitution = 0.5f},
                        .motion = {.velocity = {0.2f, 0, 0}, .angularVelocity = {0, 1.5f, 0}}});

  // Sphere-sphere, oblique.
  scene.addBody(sphere, {.position = {-0.1f, 0.3f, 0}, .velocity = {0.5f, 0, 0.1f}});
  scene.addBody(
      sphere, {.position = {-0.1f + d + gap, 0.3f + 0.3f * d, 0.002f}, .velocity = {-0.5f, 0, 0}});
  // Granule onto the floor, sliding and spinning (placed so that its lowest particle is `gap`
  // above the floor).
  scene.addBody(granule,
                {.position = {0.1f, float(0.5 * d - lowestOffset(granule, tilted)) + gap, 0.1f},
                 .orientation = tilted,
                 .velocity = {0.3f, -0.5f, 0.1f},
                 .angularVelocity = {5, 0, -3}});
  // Granule into the container's +x wall.
  scene.addBody(granule, {.position = {0.3f - reach - gap, 0.25f, 0.05f},
                          .orientation = tilted,
                          .velocity = {0.8f, 0, 0.3f},
                          .angularVelocity = {0, 4, 0}});
  // Granule outwards into the cylinder wall (from inside).
  scene.addBody(granule, {.position = {-0.15f + 0.06f - reach - gap, 0.25f, -0.15f},
                          .velocity = {0.7f, 0, 0.2f}});
  // Granule outwards and down onto the funnel's cone, 0.06 m above the outlet.
  {
    const float coneRadius = 0.02f + 0.06f * std::tan(0.6f);
    const float radial = coneRadius - (reach + gap) / std::cos(0.6f);
    scene.addBody(granule, {.position = {0.15f + radial, 0.21f, -0.15f},
                            .orientation = tilted,
                            .velocity = {0.6f, -0.3f, 0}});
  }
  // Sphere onto the rotated solid box, near an edge.
  scene.addBody(sphere, {.position = {-0.13f, 0.13f + 0.5f * d + 2.0f * gap, 0.15f},
                         .velocity = {0, -0.6f, 0.2f}});
  // Granule-granule, head on with an offset and spin.
  scene.addBody(granule, {.position = {0.0f, 0.4f, 0.15f}, .velocity = {0.5f, 0, 0}});
  scene.addBody(granule, {.position = {2 * reach + gap, 0.4f + 0.2f * d, 0.15f},
                          .orientation = tilted,
                          .velocity = {-0.5f, 0, 0},
                          .angularVelocity = {0, 0, 6}});
  // A dynamic sphere into a kinematic one (moving at constant velocity, no gravity).
  scene.addBody(sphere, {.position = {0.0f, 0.2f, -0.1f}, .velocity = {0.6f, 0, 0}});
  scene.addBody(
      sphere,
      {.position = {d + gap, 0.2f, -0.1f}, .velocity = {0.1f, 0, 0}, .motion = Motion::Kinematic});
  // A dynamic sphere onto a static granule.
  scene.addBody(granule, {.position = {-0.05f, 0.4f, -0.2f}, .motion = Motion::Static});
  scene.addBody(sphere, {.position = {-0.05f, 0.4f + reach + 0.5f * d + gap, -0.2f + 0.2f * d},
                         .velocity = {0, -0.5f, 0}});
  // Face down on the floor, its three lower particles already at the resting overlap
  // ξ = (M g / (3 k_n))^{2/3}, sliding.
  const double load = granule.mass * std::abs(double(scene.world().settings().gravity.y)) / 3.0;
  const double restHeight = lowestOffset(granule, faceDown) +
                            hertzRestingOverlap(load, scene.world().contactModel().stiffnessWall);
  scene.addBody(granule, {.position = {-0.2f, float(0.5 * d - restHeight), 0},
                          .orientation = faceDown,
                          .velocity = {0.05f, 0, 0.02f}});
  // At rest on the conveyor the same way, off its centre: the belt drags it along (μ g =
  // 4.9 m/s²) and turns it.
  scene.addBody(granule,
                {.position = {conveyorTop.x + 0.01f, conveyorTop.y + float(0.5 * d - restHeight),
                              conveyorTop.z - 0.01f},
                 .orientation = faceDown});
}
constexpr std::uint32_t kCollisionCapacity = 16;  // body slots (the scene has 15 bodies)

// --- Round-off allowances ---------------------------------------------------------------------

// How much a float evaluation of one contact may differ from the double one for the same float
// inputs (positions, velocities, spins, springs), to first order.
struct RoundOff {
  double force = 0.0;          // N
  double torque = 0.0;         // N·m, about the particle's centre (HertzMindlin)
  double spring = 0.0;         // m, the spring kept for the next substep (HertzMindlin)
  double rollingSpring = 0.0;  // m, the rolling spring kept (rolling friction)
};

// The absolute error of the GPU's float overlap ξ. A pair: ξ = d - |x_a - x_b|; the difference,
// the dot product and the square root each round, so ξ carries a few ulp of d (4), whatever ξ
// is. A collider: the centre's distance to the surface is computed from its coordinates relative
// to the collider (n·x - offset, the box frame, the axis of revolution), which round with their
// magnitude: 4 ε of it on top.
double overlapError(const OracleContact& c, const std::vector<OracleParticle>& particles,
                    const CpuOracle& oracle) {
  const double pair = 4.0 * ulp(oracle.model().diameter);
  if (c.collider == OracleContact::kCollider) return pair;
  const OracleCollider& collider = oracle.colliders()[c.collider];
  const Vec3d& x = particles[c.particle].position;
  const double scale =
      collider.kind == OracleCollider::Kind::Plane
          ? collider.normal.cwiseProduct(x).cwiseAbs().sum() + std::abs(collider.offset)
          : (x - collider.center).norm() + collider.halfExtents.maxCoeff() +
                std::max(collider.r0, collider.r1);
  return pair + 4.0 * kEps * scale;
}

// PaperViscous (eq. 9, 10). ∂F/∂ξ = 1.5 k ξ^{1/2} + ¼ γ_n ξ^{-3/4} ξ' grows without bound as
// ξ → 0 (the Tsuji damping term), so δξ is harmless for a loaded contact but large for a fresh
// one, and for a separating contact whose elastic and damping terms nearly cancel. The
// velocities' difference and projection round too (4 ε |v_rel|), which matters through γ_s for
// sticking contacts. Without this allowance 3 of the 900 pile particles failed the 1e-4 bound (a
// separating contact each, at 1.1e-3 relative error): the relative bound would have had to be
// 11× looser for every particle. With it the bound stays tight where the float inputs determine
// the force well and is honest where they do not.
RoundOff paperRoundOff(const OracleContact& c, double overlapError) {
  const double xi = std::max(c.overlap, overlapError);
  const double gammaN = c.dampingFactor * std::sqrt(c.stiffness / c.invMassSum);
  const double approach = -c.relativeVelocity.dot(c.normal);
  const double velocityError = 4.0 * kEps * c.relativeVelocity.norm();
  const double normal = 1.5 * c.stiffness * std::sqrt(xi) * overlapError +
                        gammaN * (0.25 * std::pow(xi, -0.75) * std::abs(approach) * overlapError +
                                  std::pow(xi, 0.25) * velocityError);
  // Friction follows the normal force (sliding) or the tangential velocity (sticking); the
  // arithmetic of the law itself rounds a few ε of the contact force.
  return {.force = (1.0 + c.friction) * normal + c.tangentialDamping * velocityError +
                   8.0 * kEps * c.force().norm()};
}

// HertzMindlin. The normal force as above, with η = γ_n ξ^{1/4} (0 for a new contact). v_rel is
// now a sum of surface velocities v + ω × (p - x) whose terms each round (4 ε of the sum of
// their magnitudes), and the contact point p = midpoint of two centres rounds with the
// coordinates (2 ε |x|, times the spins). The tangential trial force -k_t δ - η v_t adds:
// k_t = k_t0 √ξ, so δk_t = ½ k_t0 ξ^{-1/2} δξ (large for a fresh contact, like the damping); the
// spring's rotation into the tangent plane (8 ε |δ|) and its advance v_t dt (dt δv); δη v_t
// (η ξ^{-1} δξ / 4). A slipping contact scales the trial force to μ F_n: its error is μ δF_n
// plus at most twice the trial's (the direction's error is the trial's relative error times
// μ F_n < |trial|), and its spring -(F_t + η v_t)/k_t inherits those over k_t. The torque
// (p - x) × F rounds with the lever's error 2 ε |x| as well.
// A spring-dashpot-slider's part of that (the tangential spring's and rolling friction's): the
// trial force -k_t δ - η v from the spring turned and advanced (8 ε |δ| and dt δv), k_t's error
// and η v's; and the spring kept, the trial's, or after a slip the capped force's (the cap's
// error `capError` and twice the trial's) over k_t.
struct SliderRoundOff {
  double trial = 0.0;   // N
  double spring = 0.0;  // m
};
SliderRoundOff sliderRoundOff(double spring, double springAfter, bool slipped, double speed,
                              double speedError, double capError, double kt, double ktError,
                              double eta, double xi, double overlapError, double timeStep) {
  const double etaVError = 0.25 * eta * speed * overlapError / xi + eta * speedError;
  const double springError = 8.0 * kEps * spring + timeStep * speedError;
  SliderRoundOff out;
  out.trial = kt * springError + (spring + speed * timeStep) * ktError + etaVError;
  out.spring =
      slipped ? (capError + 2.0 * out.trial + etaVError + springAfter * ktError) / kt : springError;
  return out;
}

RoundOff mindlinRoundOff(const OracleContact& c, double overlapError, double position) {
  const double xi = std::max(c.overlap, overlapError);
  const double pointError = 2.0 * kEps * position;
  const double velocityError = 4.0 * kEps * c.velocityTerms + c.spinTerms * pointError;
  const double gammaN = c.dampingFactor * std::sqrt(c.stiffness / c.invMassSum);
  const double eta = gammaN * std::pow(xi, 0.25);
  const double approach = -c.relativeVelocity.dot(c.normal);
  const double vt = (c.relativeVelocity + approach * c.normal).norm();
  const double normal = 1.5 * c.stiffness * std::sqrt(xi) * overlapError +
                        0.25 * gammaN * std::pow(xi, -0.75) * std::abs(approach) * overlapError +
                        eta * velocityError;
  const double kt = c.shearStiffness * std::sqrt(xi);
  const double ktError = 0.5 * c.shearStiffness / std::sqrt(xi) * overlapError;
  const oracle::MindlinResult r = c.evaluate();
  const SliderRoundOff tangential =
      sliderRoundOff(c.spring.norm(), r.spring.norm(), r.slipping, vt, velocityError,
                     c.friction * normal, kt, ktError, eta, xi, overlapError, c.timeStep);
  RoundOff out;
  out.force = (1.0 + c.friction) * normal + 2.0 * tangential.trial + 8.0 * kEps * r.force.norm();
  out.torque = c.lever.norm() * out.force + r.force.norm() * pointError;
  out.spring = tangential.spring;
  // Rolling friction's spring and couple R n × F_r, the same with the rolling velocity
  // v_r = R (w × n), whose spins round with their terms (4 ε of their magnitudes).
  const oracle::RollingResult rolling = c.rolling(r);
  if (c.rollingFriction > 0.0) {
    const double radius = c.rollingRadius;
    const double vr = radius * c.relativeSpin.cross(c.normal).norm();
    const double vrError = radius * (4.0 * kEps * c.spinTerms + 2.0 * kEps * c.relativeSpin.norm());
    const double cap = c.rollingFriction * normal;
    const SliderRoundOff slider =
        sliderRoundOff(c.rollingSpring.norm(), rolling.spring.norm(), rolling.rolls, vr, vrError,
                       cap, kt, ktError, eta, xi, overlapError, c.timeStep);
    const double forceError = rolling.rolls ? cap + 2.0 * slider.trial : slider.trial;
    out.torque += radius * forceError + 8.0 * kEps * rolling.torque.norm();
    out.rollingSpring = slider.spring;
  }
  return out;
}

// --- One substep ------------------------------------------------------------------------------

// The particle state the GPU's last substep computed its forces from (World::readParticles
// read before that substep: the state it starts from), with what the kernel took from the
// bodies: the spins of before that substep (the oracle built then, `before`) and the inverse
// masses as uploaded.
std::vector<OracleParticle> gpuParticles(const std::vector<ParticleState>& gpu,
                                         const CpuOracle& before) {
  std::vector<OracleParticle> particles;
  for (std::uint32_t i = 0; i < gpu.size(); ++i) {
    // The oracle's bodies and particles are in the GPU's slot order (OracleScene::oracle).
    const std::uint32_t slot = before.particleBody(i);
    const OracleBody& body = before.bodies()[slot];
    EXPECT_EQ(body.id, gpu[i].body.index) << "particle " << i;
    particles.push_back({slot, toDouble(gpu[i].position), toDouble(gpu[i].velocity),
                         body.angularVelocity, body.particleInverseMass(before.model().law)});
  }
  return particles;
}

struct ForceComparison {
  std::size_t particles = 0;
  std::size_t failures = 0;
  double worstFractionOfTolerance = 0.0;  // max |ΔF| / tolerance
  double maxRelativeError = 0.0;          // max |ΔF| / |F| over particles with |F| >= floor
  double maxAbsoluteError = 0.0;          // N
  std::size_t contactEnds = 0;            // particle-particle contacts seen from each side
  std::size_t colliderContacts = 0;
  std::vector<double> tolerance;                   // per particle, N
  std::vector<double> torqueAllowance;             // per particle, N·m (HertzMindlin)
  std::map<ContactKey, RoundOff> springAllowance;  // per contact: spring, rollingSpring
};

// Tolerance: |F_gpu - F_cpu| <= 1e-4 · max(|F_cpu|, floor) + the round-off allowance (above).
// Floor: 1e-3 of a particle's weight (1.1e-4 N at the default material); below it a relative
// bound means nothing (a particle with no contact has F = 0 on both sides, exactly). What each
// scene measured is stated at its test.
constexpr double kRelativeForceTolerance = 1e-4;

// Pass 2 of the oracle (`before`: bodies and history of before the GPU's last substep) on
// exactly the particle state that substep computed its forces from (`particles`, from `gpu`,
// World::readParticles), compared particle by particle.
ForceComparison compareForces(const World& world, const CpuOracle& before,
                              const std::vector<ParticleState>& gpu,
                              const std::vector<OracleParticle>& particles) {
  const bool mindlin = before.model().law == ContactLaw::HertzMindlin;
  std::vector<Vec3d> force(particles.size(), Vec3d::Zero());
  std::vector<double> allowance(particles.size(), 0.0);
  ForceComparison result;
  result.particles = particles.size();
  result.torqueAllowance.assign(particles.size(), 0.0);
  for (const OracleContact& c : before.findContacts(particles)) {
    force[c.particle] += c.force();
    const double dXi = overlapError(c, particles, before);
    const RoundOff r =
        mindlin ? mindlinRoundOff(c, dXi,
                                  particles[c.particle].position.norm() + before.model().diameter)
                : paperRoundOff(c, dXi);
    allowance[c.particle] += r.force;
    result.torqueAllowance[c.particle] += r.torque;
    if (mindlin) result.springAllowance[{std::uint32_t(c.particle), c.key}] = r;
    ++(c.other == OracleContact::kCollider ? result.colliderContacts : result.contactEnds);
  }
  const double floor = 1e-3 * particleWeight(world);
  result.tolerance.resize(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double error = (toDouble(gpu[i].force) - force[i]).norm();
    const double magnitude = force[i].norm();
    const double tolerance = kRelativeForceTolerance * std::max(magnitude, floor) + allowance[i];
    result.tolerance[i] = tolerance;
    result.maxAbsoluteError = std::max(result.maxAbsoluteError, error);
    if (magnitude >= floor)
      result.maxRelativeError = std::max(result.maxRelativeError, error / magnitude);
    result.worstFractionOfTolerance = std::max(result.worstFractionOfTolerance, error / tolerance);
    if (error > tolerance) ++result.failures;
  }
  return result;
}

void print(const ForceComparison& r, const char* what) {
  std::printf(
      "[ oracle ] %s: %zu particles, %zu pair contacts, %zu collider contacts: max |dF|/|F| "
      "%.3g, max |dF| %.3g N, worst %.3g of the tolerance, %zu fail\n",
      what, r.particles, r.contactEnds / 2, r.colliderContacts, r.maxRelativeError,
      r.maxAbsoluteError, r.worstFractionOfTolerance, r.failures);
}

// The body pass of that substep: each dynamic body's change of velocity and of spin on the GPU
// against the oracle's passes 2 and 3 from the same particle state. The spin is where the
// HertzMindlin torque of friction at the contact points shows (the GPU gives no per-particle
// torque back).
struct BodyPassComparison {
  std::size_t bodies = 0;
  std::size_t failures = 0;
  double worstVelocityFraction = 0.0;  // max |Δv_gpu - Δv_cpu| / tolerance
  double worstSpinFraction = 0.0;      // max |Δω_gpu - Δω_cpu| / tolerance
  double maxSpinError = 0.0;           // rad/s
  // The part of Δω that the torques of friction at the contact points make (dropping them would
  // move Δω by this much): bodies where it is above 10 spin tolerances, and its largest ratio.
  std::size_t contactTorqueVisible = 0;
  double maxContactTorqueFraction = 0.0;
};

// Tolerances: the per-particle force tolerance of compareForces carried through the sums,
// Δv: dt Σ tol_k / M, and Δω: dt (Σ |x_k - c| tol_k + torque allowances) / min(I), plus the
// rounding of the float updates themselves (v += dt (F/M + g): 4 ε |v|; ω to the principal frame
// and back: 8 ε |ω|) and 1e-4 of the change.
BodyPassComparison compareBodyPass(const World& world, const CpuOracle& before,
                                   const CpuOracle& after,
                                   const std::vector<OracleParticle>& particles,
                                   const ContactPass& pass, const ForceComparison& forces) {
  BodyPassComparison result;
  const std::vector<BodyState> gpu = world.readBodies();
  const double dt = before.model().timeStep;
  std::size_t first = 0;
  for (std::size_t b = 0; b < before.bodies().size(); ++b) {
    const OracleBody& body = before.bodies()[b];
    const std::size_t count = body.offsets.size();
    const std::size_t end = first + count;
    if (body.motion != Motion::Dynamic) {
      first = end;
      continue;
    }
    double forceTolerance = 0.0;
    double torqueTolerance = 0.0;
    Vec3d contactTorque = Vec3d::Zero();
    for (std::size_t k = first; k < end; ++k) {
      const double arm = (particles[k].position - body.position).norm();
      forceTolerance += forces.tolerance[k];
      torqueTolerance += arm * forces.tolerance[k] + forces.torqueAllowance[k] +
                         4.0 * kEps * arm * pass.force[k].norm();
      contactTorque += pass.torque[k];
    }
    first = end;
    const Vec3d dvCpu = after.bodies()[b].velocity - body.velocity;
    const Vec3d dvGpu = toDouble(gpu[body.id].velocity) - body.velocity;
    const Vec3d dwCpu = after.bodies()[b].angularVelocity - body.angularVelocity;
    const Vec3d dwGpu = toDouble(gpu[body.id].angularVelocity) - body.angularVelocity;
    const double minInertia = body.principalInertia.minCoeff();
    const double vTolerance =
        dt * forceTolerance / body.mass + 4.0 * kEps * body.velocity.norm() + 1e-4 * dvCpu.norm();
    const double wTolerance = dt * torqueTolerance / minInertia +
                              8.0 * kEps * body.angularVelocity.norm() + 1e-4 * dwCpu.norm();
    const double vFraction = (dvGpu - dvCpu).norm() / vTolerance;
    const double wFraction = (dwGpu - dwCpu).norm() / wTolerance;
    ++result.bodies;
    if (vFraction > 1.0 || wFraction > 1.0) ++result.failures;
    result.worstVelocityFraction = std::max(result.worstVelocityFraction, vFraction);
    result.worstSpinFraction = std::max(result.worstSpinFraction, wFraction);
    result.maxSpinError = std::max(result.maxSpinError, (dwGpu - dwCpu).norm());
    // What the contact-point torques alone change ω by: R I^{-1} R^T dt Σ τ_k.
    const Vec3d local = oracle::rotateInverse(body.orientation, dt * contactTorque);
    const double effect =
        oracle::rotate(body.orientation, local.cwiseQuotient(body.principalInertia)).norm();
    result.maxContactTorqueFraction =
        std::max(result.maxContactTorqueFraction, effect / wTolerance);
    if (effect > 10.0 * wTolerance) ++result.contactTorqueVisible;
  }
  return result;
}

// The contact history after that substep: the GPU's slots (World::readSnapshot) against the
// oracle's, contact by contact: the same contacts, the same pair counts (integers, exactly),
// and springs (and rolling springs) within 1e-4 max(|δ|, 1 µm) + their round-off allowance
// (mindlinRoundOff).
struct HistoryComparison {
  std::size_t contacts = 0;  // in the oracle's history
  std::size_t missing = 0;   // in the oracle's, not in the GPU's
  std::size_t extra = 0;     // in the GPU's, not in the oracle's
  std::size_t pairMismatches = 0;
  std::size_t springFailures = 0;  // the tangential or (rolling friction) the rolling spring
  double maxSpringError = 0.0;     // m
  double worstSpringFraction = 0.0;
  double maxRollingSpringError = 0.0;  // m
  double worstRollingSpringFraction = 0.0;
  std::size_t sharedPairs = 0;  // contacts with n > 1 (the count matters)
};

HistoryComparison compareHistory(const World& world, const CpuOracle& after,
                                 const ForceComparison& forces) {
  HistoryComparison result;
  const ContactHistoryMap gpu = oracle::historyFromSnapshot(world.readSnapshot());
  for (const auto& [key, h] : after.history()) {
    ++result.contacts;
    if (h.pairs > 1) ++result.sharedPairs;
    const auto it = gpu.find(key);
    if (it == gpu.end()) {
      ++result.missing;
      continue;
    }
    if (it->second.pairs != h.pairs) ++result.pairMismatches;
    const auto found = forces.springAllowance.find(key);
    const RoundOff allowance = found == forces.springAllowance.end() ? RoundOff{} : found->second;
    const double error = (it->second.spring - h.spring).norm();
    const double tolerance = 1e-4 * std::max(h.spring.norm(), 1e-6) + allowance.spring;
    result.maxSpringError = std::max(result.maxSpringError, error);
    result.worstSpringFraction = std::max(result.worstSpringFraction, error / tolerance);
    const double rollingError = (it->second.rollingSpring - h.rollingSpring).norm();
    const double rollingTolerance =
        1e-4 * std::max(h.rollingSpring.norm(), 1e-6) + allowance.rollingSpring;
    result.maxRollingSpringError = std::max(result.maxRollingSpringError, rollingError);
    result.worstRollingSpringFraction =
        std::max(result.worstRollingSpringFraction, rollingError / rollingTolerance);
    if (error > tolerance || rollingError > rollingTolerance) ++result.springFailures;
  }
  for (const auto& entry : gpu) {
    if (!after.history().contains(entry.first)) ++result.extra;
  }
  return result;
}

// One GPU substep against the oracle from the same state: `oracle` holds the bodies, spins and
// history the GPU held before it (scene.oracle()); the particle positions and velocities are the
// GPU's own of that substep, so that pass 1's rounding does not enter. On return `oracle` has run
// passes 2 and 3 from them: it is one substep on, with the GPU.
struct SubstepComparison {
  ForceComparison forces;
  BodyPassComparison bodies;
  HistoryComparison history;
  std::vector<ContactRecord> contacts;  // World::readContacts before the substep: its contacts
};

SubstepComparison compareOneSubstep(World& world, CpuOracle& oracle) {
  const CpuOracle before = oracle;
  // The state the substep starts from and the contacts it will apply, then its forces.
  std::vector<ParticleState> gpu = world.readParticles();
  SubstepComparison result;
  result.contacts = world.readContacts();
  world.substep(1);
  const std::vector<ParticleState> after = world.readParticles();
  for (std::size_t i = 0; i < gpu.size(); ++i) gpu[i].force = after[i].force;
  const std::vector<OracleParticle> particles = gpuParticles(gpu, before);
  result.forces = compareForces(world, before, gpu, particles);
  oracle.step(particles);
  result.bodies = compareBodyPass(world, before, oracle, particles, before.contactPass(particles),
                                  result.forces);
  if (before.model().law == ContactLaw::HertzMindlin) {
    result.history = compareHistory(world, oracle, result.forces);
  }
  return result;
}

void print(const SubstepComparison& r, const char* what) {
  print(r.forces, what);
  std::printf(
      "[ oracle ] %s: %zu bodies: worst dv %.3g, dw %.3g of the tolerance (max |dw| error %.3g "
      "rad/s), %zu fail; contact-point torque above 10 tolerances in %zu bodies (up to %.3g)\n",
      what, r.bodies.bodies, r.bodies.worstVelocityFraction, r.bodies.worstSpinFraction,
      r.bodies.maxSpinError, r.bodies.failures, r.bodies.contactTorqueVisible,
      r.bodies.maxContactTorqueFraction);
  std::printf(
      "[ oracle ] %s: history %zu contacts (%zu with n > 1), %zu missing, %zu extra, %zu pair "
      "counts differ; max spring error %.3g m, worst %.3g of the tolerance; rolling springs %.3g "
      "m, %.3g; %zu fail\n",
      what, r.history.contacts, r.history.sharedPairs, r.history.missing, r.history.extra,
      r.history.pairMismatches, r.history.maxSpringError, r.history.worstSpringFraction,
      r.history.maxRollingSpringError, r.history.worstRollingSpringFraction,
      r.history.springFailures);
}

void expectMatch(const SubstepComparison& r) {
  EXPECT_EQ(r.forces.failures, 0u)
      << "particles whose GPU force is off the oracle's beyond round-off; worst at "
      << r.forces.worstFractionOfTolerance << " of its tolerance";
  EXPECT_EQ(r.bodies.failures, 0u) << "bodies whose GPU velocity or spin change is off the "
                                      "oracle's beyond round-off; worst at "
                                   << r.bodies.worstVelocityFraction << " (dv), "
                                   << r.bodies.worstSpinFraction << " (dw) of the tolerance";
  EXPECT_EQ(r.history.missing, 0u);
  EXPECT_EQ(r.history.extra, 0u);
  EXPECT_EQ(r.history.pairMismatches, 0u);
  EXPECT_EQ(r.history.springFailures, 0u)
      << "worst spring at " << r.history.worstSpringFraction << " of its tolerance";
}

// --- 1. Forces at one substep ---------------------------------------------------------------

// The pile after 1999 substeps, HertzMindlin: 277 pair and 50 collider contacts, 604 slots of
// history (309 of them shared, n > 1). Measured (llvmpipe): forces max |dF|/|F| = 2.1e-3, max
// |dF| = 4.7e-5 N, the worst particle at 9.4% of its tolerance; body pass: the worst Δv at 18%,
// the worst Δω at 48% of its tolerance (max error 1.1e-5 rad/s, mostly the float update of ω,
// 8 ε |ω|), while the torques of friction at the contact points alone move Δω by more than 10
// tolerances in 163 of the 225 granules (up to 1800×); history: the same 604 keys and pair
// counts, springs within 7.4e-8 m, the worst at 8.4% of its tolerance. ~3.5 s.
TEST(OracleForces, PileForcesMatchTheOracleAtOneSubstep) {
  OracleScene scene(300, ContactLaw::HertzMindlin);
  buildPile(scene, kPileSubsteps);
  CpuOracle oracle = scene.oracle();
  const SubstepComparison r = compareOneSubstep(scene.world(), oracle);
  print(r, "pile, one substep");
  EXPECT_GE(r.forces.contactEnds / 2 + r.forces.colliderContacts, 300u) << "not a pile yet";
  expectMatch(r);
  EXPECT_GT(r.history.sharedPairs, 100u) << "the pair counts n are hardly exercised";
  EXPECT_GT(r.bodies.contactTorqueVisible, r.bodies.bodies / 4)
      << "the spin comparison would not notice a missing contact-point torque";

  // The GPU finds the same contacts: its list (each pair once) against the oracle's O(n²) search.
  std::size_t gpuPairs = 0, gpuColliders = 0;
  for (const ContactRecord& c : r.contacts) {
    ++(c.particleB == ContactRecord::kNone ? gpuColliders : gpuPairs);
  }
  EXPECT_EQ(gpuPairs, r.forces.contactEnds / 2);
  EXPECT_EQ(gpuColliders, r.forces.colliderContacts);
}

// The pile with rolling friction (mu_r = 0.3): the couples against the bodies' relative rolling,
// as the oracle evaluates them, and without them the spins are off. ~4 s.
TEST(OracleForces, RollingFrictionPileMatchesTheOracleAtOneSubstep) {
  constexpr float kRollingFriction = 0.3f;
  OracleScene scene(300, ContactLaw::HertzMindlin, kRollingFriction);
  buildPile(scene, kPileSubsteps);
  CpuOracle oracle = scene.oracle();
  ASSERT_EQ(oracle.model().rollingFriction, double(kRollingFriction));
  const SubstepComparison r = compareOneSubstep(scene.world(), oracle);
  print(r, "pile with rolling friction, one substep");
  expectMatch(r);

  OracleScene same(300, ContactLaw::HertzMindlin, kRollingFriction);
  buildPile(same, kPileSubsteps);
  CpuOracle without = same.oracle();
  without.model().rollingFriction = 0.0;
  const SubstepComparison w = compareOneSubstep(same.world(), without);
  print(w, "pile with rolling friction, the oracle without it");
  EXPECT_EQ(w.forces.failures, 0u) << "a couple moves no particle's force";
  EXPECT_GT(w.bodies.failures, w.bodies.bodies / 10)
      << "the spin comparison would not notice a missing rolling couple";
}

// The isolated collisions at a few moments: pairs (including the kinematic and the static
// partner) and walls mid-impact (40, 60, 80 substeps), the floor granule sliding and the
// conveyor dragging its granule (150), the floor granule sticking (400). Measured (llvmpipe),
// worst over the five: forces at 2.3% of the tolerance (max |dF|/|F| = 8.9e-6); Δv at 3%, Δω at
// 31%; the same keys and pair counts, springs at 2.1% of the tolerance. ~0.5 s.
TEST(OracleForces, IsolatedCollisionForcesMatchTheOracleAtOneSubstep) {
  OracleScene scene(kCollisionCapacity, ContactLaw::HertzMindlin);
  buildCollisions(scene);
  std::uint32_t done = 0;
  for (const std::uint32_t at : {40u, 60u, 80u, 150u, 400u}) {
    scene.world().substep(at - done - 1);
    CpuOracle oracle = scene.oracle();
    const SubstepComparison r = compareOneSubstep(scene.world(), oracle);
    done = at;
    char what[64];
    std::snprintf(what, sizeof what, "collisions, substep %u", at);
    print(r, what);
    expectMatch(r);
  }
}

// PaperViscous, the pile: the law without history (328 pair and 57 collider contacts).
// Measured (llvmpipe): max |dF|/|F| = 5.4e-4, max |dF| = 4.3e-5 N, the worst particle at 10% of
// its tolerance (12% at the previous substep, when the tolerance was chosen). ~1.6 s.
TEST(OracleForces, PaperViscousPileForcesMatchTheOracleAtOneSubstep) {
  OracleScene scene(300, ContactLaw::PaperViscous);
  buildPile(scene, kPileSubsteps);
  CpuOracle oracle = scene.oracle();
  const SubstepComparison r = compareOneSubstep(scene.world(), oracle);
  print(r.forces, "paper law pile, one substep");
  EXPECT_GE(r.forces.contactEnds / 2 + r.forces.colliderContacts, 300u) << "not a pile yet";
  EXPECT_EQ(r.forces.failures, 0u)
      << "particles whose GPU force is off the oracle's beyond round-off; worst at "
      << r.forces.worstFractionOfTolerance << " of its tolerance";
  EXPECT_EQ(r.bodies.failures, 0u);
}

// --- 2. Trajectories over 500 substeps ------------------------------------------------------

struct Divergence {
  double position = 0.0;         // m, max over bodies
  double velocity = 0.0;         // m/s
  double angularVelocity = 0.0;  // rad/s
  double orientation = 0.0;      // rad, angle of q_gpu · q_cpu*
};

Divergence compareBodies(const World& world, const CpuOracle& oracle) {
  Divergence d;
  const std::vector<BodyState> gpu = world.readBodies();
  for (const OracleBody& b : oracle.bodies()) {
    const BodyState& s = gpu[b.id];
    d.position = std::max(d.position, (toDouble(s.position) - b.position).norm());
    d.velocity = std::max(d.velocity, (toDouble(s.velocity) - b.velocity).norm());
    d.angularVelocity =
        std::max(d.angularVelocity, (toDouble(s.angularVelocity) - b.angularVelocity).norm());
    // The angle of q_gpu · q_cpu*, from its vector part: acos of the dot product would turn the
    // float quaternion's norm error (~1e-8) into a fake angle of ~1e-4 rad.
    const oracle::QuatD c = b.templateOrientation();
    const oracle::QuatD r = oracle::multiply(toDouble(s.orientation), {c.w, -c.x, -c.y, -c.z});
    const double angle = 2.0 * std::atan2(Vec3d(r.x, r.y, r.z).norm(), std::abs(r.w));
    d.orientation = std::max(d.orientation, angle);
  }
  return d;
}

void print(const char* what, const Divergence& d) {
  std::printf(
      "[ oracle ] %s: position %.3g m, velocity %.3g m/s, spin %.3g rad/s, angle %.3g rad\n", what,
      d.position, d.velocity, d.angularVelocity, d.orientation);
}

struct TrajectoryTolerance {
  double position;         // m
  double velocity;         // m/s
  double angularVelocity;  // rad/s
  double orientation;      // rad
};

void expectWithin(const Divergence& d, const TrajectoryTolerance& t) {
  EXPECT_LT(d.position, t.position);
  EXPECT_LT(d.velocity, t.velocity);
  EXPECT_LT(d.angularVelocity, t.angularVelocity);
  EXPECT_LT(d.orientation, t.orientation);
}

// The oracle and the GPU each run `substeps` from the state the GPU holds now.
Divergence runBoth(OracleScene& scene, CpuOracle& oracle, std::uint32_t substeps) {
  oracle.step(int(substeps));
  scene.world().substep(substeps);
  return compareBodies(scene.world(), oracle);
}

// Pile, 500 substeps (~33 ms) from the read-back state (bodies and contact history). Float and
// double part at once: every substep rounds every float quantity (≤ 500 · ½ ulp(0.4 m) =
// 7.5e-6 m of position from the sums x += dt v alone), and granular contacts amplify
// differences (stiff Hertz contacts, springs that stick or slip): ×2 to ×3 per 50 substeps
// here, faster than under the paper's law (4.8e-6 m after 500), since sticking springs couple
// the grains stiffly. Rounding explains all of it: the double oracle whose body states and springs
// were rounded to float after every substep drifted from the exact one by 6.0e-5 m, 8.4e-3 m/s,
// 0.77 rad/s (one ulp in each body's x alone, once: 1.1e-6 m, 5e-4 m/s, 0.07 rad/s). How far
// the amplification carries it varies from one state of the pile to the next: over twenty
// (the pile after 1599 to 1999 substeps, with and without sorts of the granules, on Mesa 22.3
// and 25.0) the GPU ended 1.3e-5 to 1.3e-4 m, 6.4e-3 to 4.9e-2 m/s, 0.65 to 6.0 rad/s and
// 1.8e-3 to 1.5e-2 rad from the oracle. Tolerances: 1.6 to 2.3 times the worst of them. Friction
// 10% off gives 6.5e-3 m, 0.59 m/s, 47 rad/s, 0.47 rad: 22×, 7.3×, 4.7×, 19× the tolerances
// (OracleSensitivity). ~5 s.
constexpr TrajectoryTolerance kPileTolerance{
    .position = 3e-4, .velocity = 8e-2, .angularVelocity = 10.0, .orientation = 2.5e-2};

TEST(OracleTrajectories, PileFollowsTheOracleFor500Substeps) {
  OracleScene scene(300, ContactLaw::HertzMindlin);
  buildPile(scene, kPileSubsteps);
  CpuOracle oracle = scene.oracle();
  EXPECT_GT(oracle.history().size(), 500u) << "the oracle should start from the GPU's history";
  const Divergence d = runBoth(scene, oracle, 500);
  print("pile after 500 substeps", d);
  expectWithin(d, kPileTolerance);
}

// Isolated collisions, 500 substeps, HertzMindlin, from a World that never stepped (no history
// yet): no crowd amplifies the round-off, but these bodies sit up to 0.4 m from the origin and
// fly at up to 0.8 m/s, so the float sums x += dt v and v += dt g alone drift by up to
// 500 · ½ ulp: 7.5e-6 m and 1.5e-5 m/s. Measured: 4.5e-6 m, 1.5e-4 m/s, 4.4e-3 rad/s,
// 1.0e-4 rad. Tolerances: the position at 2.7× the float-sum bound, the rest 3.3× to 5× the
// measurement. Friction 10% off gives 4.2e-4 m, 0.020 m/s, 2.1 rad/s, 0.051 rad (21× and 39× the
// position and velocity tolerances). ~0.3 s.
constexpr TrajectoryTolerance kCollisionTolerance{
    .position = 2e-5, .velocity = 5e-4, .angularVelocity = 0.02, .orientation = 5e-4};

void expectEveryBodyCollided(OracleScene& scene, const std::vector<OracleBody>& before,
                             const CpuOracle& oracle) {
  // Every dynamic body did collide: its velocity left free flight by a clear margin.
  const double t = 500.0 * scene.world().timeStep();
  const Vec3d gravity = OracleModel::fromWorld(scene.world()).gravity;
  for (std::size_t b = 0; b < before.size(); ++b) {
    if (before[b].motion != Motion::Dynamic) continue;
    const Vec3d ballistic = before[b].velocity + t * gravity;
    EXPECT_GT((oracle.bodies()[b].velocity - ballistic).norm(), 0.05)
        << "body " << b << " never touched anything";
  }
}

TEST(OracleTrajectories, IsolatedCollisionsFollowTheOracleFor500Substeps) {
  OracleScene scene(kCollisionCapacity, ContactLaw::HertzMindlin);
  buildCollisions(scene);
  CpuOracle oracle = scene.oracle();
  const std::vector<OracleBody> before = oracle.bodies();
  const Divergence d = runBoth(scene, oracle, 500);
  print("isolated collisions after 500 substeps", d);
  expectWithin(d, kCollisionTolerance);
  expectEveryBodyCollided(scene, before, oracle);

  // The lasting contacts exercise every state of the law's history: the floor granule's slip
  // and then stick; the conveyor's slip all along, and the belt drags its granule.
  const std::size_t sliding = before.size() - 2, riding = before.size() - 1;
  for (const std::size_t b : {sliding, riding}) {
    const oracle::ContactTally& t = oracle.tally(b);
    std::printf("[ oracle ] body %zu: contact-substeps %llu new, %llu sticking, %llu slipping\n", b,
                static_cast<unsigned long long>(t.fresh),
                static_cast<unsigned long long>(t.sticking),
                static_cast<unsigned long long>(t.slipping));
  }
  std::printf("[ oracle ] floor granule v (%.4f %.4f %.4f), conveyor granule v (%.4f %.4f %.4f)\n",
              oracle.bodies()[sliding].velocity.x(), oracle.bodies()[sliding].velocity.y(),
              oracle.bodies()[sliding].velocity.z(), oracle.bodies()[riding].velocity.x(),
              oracle.bodies()[riding].velocity.y(), oracle.bodies()[riding].velocity.z());
  EXPECT_GT(oracle.tally(sliding).sticking, 100u);
  EXPECT_GT(oracle.tally(sliding).slipping, 100u);
  EXPECT_GT(oracle.tally(riding).slipping, 500u);
  EXPECT_GT(oracle.bodies()[riding].velocity.x(), 0.1);
}

// PaperViscous, the same collisions (the conveyor's motion does not enter this law on the GPU,
// nor in the oracle: contacts.comp passes the particle's own velocity to contactForce). Measured:
// 1.4e-6 m, 6.7e-5 m/s, 7.0e-3 rad/s, 1.6e-4 rad (without the two lasting contacts, when the
// tolerances were chosen: 4.1e-6 m, 5.8e-5 m/s, 2.4e-3 rad/s, 6.8e-5 rad; one ulp of change in
// the initial state moved the oracle's own result by 5e-8 m and 1.4e-6 m/s: the per-substep
// rounding dominates). Tolerances: the position at 2.7× the float-sum bound, the velocity 7.5×,
// spin and angle 3× the measurement. Grain friction 10% off gives 1.5e-4 m and 0.010 m/s (7.7×
// and 21× the tolerances); normal damping 10% off gave 4e-4 m and 0.015 m/s. ~0.3 s.
constexpr TrajectoryTolerance kPaperCollisionTolerance{
    .position = 2e-5, .velocity = 5e-4, .angularVelocity = 0.02, .orientation = 5e-4};

TEST(OracleTrajectories, PaperViscousIsolatedCollisionsFollowTheOracleFor500Substeps) {
  OracleScene scene(kCollisionCapacity, ContactLaw::PaperViscous);
  buildCollisions(scene);
  CpuOracle oracle = scene.oracle();
  const std::vector<OracleBody> before = oracle.bodies();
  const Divergence d = runBoth(scene, oracle, 500);
  print("paper law isolated collisions after 500 substeps", d);
  expectWithin(d, kPaperCollisionTolerance);
  expectEveryBodyCollided(scene, before, oracle);
}

// --- 3. The comparison can fail -------------------------------------------------------------

// The same comparisons against an oracle whose friction coefficients (the grains' and every
// collider's) are 10% high must fail, by a clear factor, or the tolerances hide model errors.
// Measured, HertzMindlin pile at one substep: 274 of 900 particle forces fail, the worst at 791×
// its tolerance; Δv and Δω up to 322× and 212×; springs up to 1.5e4×. Over 500 substeps see the
// trajectory tests. ~8 s. PaperViscous pile: 379 of 900 forces fail, the worst at 604×. ~4 s.
void scaleFriction(CpuOracle& oracle, double factor) {
  oracle.model().friction *= factor;
  for (OracleCollider& c : oracle.colliders()) c.friction *= factor;
}

TEST(OracleSensitivity, TenPercentMoreFrictionFailsEveryComparison) {
  {
    OracleScene scene(300, ContactLaw::HertzMindlin);
    buildPile(scene, kPileSubsteps);
    CpuOracle wrong = scene.oracle();
    scaleFriction(wrong, 1.1);
    const SubstepComparison r = compareOneSubstep(scene.world(), wrong);
    print(r, "pile, friction x1.1");
    EXPECT_GT(r.forces.failures, r.forces.particles / 10);
    EXPECT_GT(r.forces.worstFractionOfTolerance, 100.0);
    EXPECT_GT(r.bodies.failures, r.bodies.bodies / 10);
    EXPECT_GT(r.history.springFailures, r.history.contacts / 10);
    const Divergence d = runBoth(scene, wrong, 499);
    print("pile, friction x1.1", d);
    EXPECT_GT(d.position, 5.0 * kPileTolerance.position);
    EXPECT_GT(d.velocity, 5.0 * kPileTolerance.velocity);
  }
  {
    OracleScene scene(kCollisionCapacity, ContactLaw::HertzMindlin);
    buildCollisions(scene);
    CpuOracle wrong = scene.oracle();
    scaleFriction(wrong, 1.1);
    const Divergence d = runBoth(scene, wrong, 500);
    print("isolated collisions, friction x1.1", d);
    EXPECT_GT(d.position, 5.0 * kCollisionTolerance.position);
    EXPECT_GT(d.velocity, 5.0 * kCollisionTolerance.velocity);
  }
}

TEST(OracleSensitivity, PaperViscousTenPercentMoreFrictionFailsBothComparisons) {
  {
    OracleScene scene(300, ContactLaw::PaperViscous);
    buildPile(scene, kPileSubsteps);
    CpuOracle wrong = scene.oracle();
    scaleFriction(wrong, 1.1);
    const SubstepComparison r = compareOneSubstep(scene.world(), wrong);
    print(r.forces, "paper law pile, friction x1.1");
    EXPECT_GT(r.forces.failures, r.forces.particles / 4);
    EXPECT_GT(r.forces.worstFractionOfTolerance, 100.0);
  }
  {
    OracleScene scene(kCollisionCapacity, ContactLaw::PaperViscous);
    buildCollisions(scene);
    CpuOracle wrong = scene.oracle();
    scaleFriction(wrong, 1.1);
    const Divergence d = runBoth(scene, wrong, 500);
    print("paper law isolated collisions, friction x1.1", d);
    EXPECT_GT(d.position, 5.0 * kPaperCollisionTolerance.position);
    EXPECT_GT(d.velocity, 5.0 * kPaperCollisionTolerance.velocity);
  }
}

}  // namespace
}  // namespace sandphys
