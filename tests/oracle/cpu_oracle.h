#pragma once

// A readable double-precision CPU oracle of exactly the model the GPU step runs (shaders/sim/):
// plain O(n²) loops, no grid, no float. It exists so that the oracle tests can tell a real model
// difference in the kernels (a wrong sign, a missing term, a missed neighbour) from float
// round-off. Both contact laws (WorldSettings::contactLaw): ContactLaw::HertzMindlin, with its
// per-contact history, and ContactLaw::PaperViscous (eq. 9, 10), which keeps none. One step
// mirrors World's substep pass by pass:
//   1. particles from bodies          (eq. 7, 8)           bodies_to_particles.comp
//   2. contact and collider forces    (eq. 9, 10 or        contacts.comp, contact_law.glsl,
//      (and, HertzMindlin, torques      Hertz-Mindlin)     colliders.glsl, contact_slots.glsl
//      and contact history)
//   3. body sums and integration      (eq. 2-6)            integrate_bodies.comp,
//      (and, HertzMindlin, the pair                        integrate_large_bodies.comp,
//      counts of the new history)                          rigid_motion.glsl, contact_pairs.glsl
// Left out: sinks and emitters (no oracle scene uses them), the grid by design (the O(n²) search
// finds every neighbour that the GPU's hashed gather should find), and the GPU's limit of
// kContactSlots contacts with history per particle (the oracle keeps every contact's; the oracle
// scenes stay below the limit).

#include <Eigen/Dense>

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::oracle {

using Vec3d = Eigen::Vector3d;

/// A unit quaternion (w, x, y, z) in double: the rotation from a body's principal frame to the
/// world.
struct QuatD {
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

Vec3d toDouble(Vec3 v);
QuatD toDouble(Quat q);
/// q · v · q*: principal frame to world.
Vec3d rotate(const QuatD& q, const Vec3d& v);
/// q* · v · q: world to principal frame.
Vec3d rotateInverse(const QuatD& q, const Vec3d& v);
/// The Hamilton product a · b.
QuatD multiply(const QuatD& a, const QuatD& b);

/// The numbers of the contact law and the integrator, in double. Built from a World so that the
/// oracle runs the very constants the GPU was given (they are float there; the oracle widens
/// them, it does not recompute them).
struct OracleModel {
  ContactLaw law = ContactLaw::HertzMindlin;
  double radius = 0.0;    ///< particle radius r, m
  double diameter = 0.0;  ///< particle diameter d = contact distance, m
  /// PaperViscous: penetration guard ξ_max = d/10, m; HertzMindlin: +infinity (no guard).
  double maxOverlap = 0.0;
  double stiffnessGrain = 0.0;       ///< k_n grain-grain, N/m^{3/2}
  double stiffnessWall = 0.0;        ///< k_n grain-collider, N/m^{3/2}
  double shearStiffnessGrain = 0.0;  ///< HertzMindlin: k_t0 grain-grain (k_t = k_t0 √ξ), N/m^{3/2}
  double shearStiffnessWall = 0.0;  ///< HertzMindlin: k_t0 grain-collider, N/m^{3/2}
  double dampingFactorGrain = 0.0;  ///< c(e) grain-grain, dimensionless
  double friction = 0.0;            ///< μ grain-grain
  double rollingFriction = 0.0;     ///< HertzMindlin: μ_r, every contact
  double tangentialDamping = 0.0;   ///< PaperViscous: γ_s, N·s/m (grain-grain and collider)
  double timeStep = 0.0;            ///< s
  double maxSpeed = 0.0;            ///< speed guard, m/s
  Vec3d gravity = Vec3d::Zero();    ///< m/s²

  static OracleModel fromWorld(const World& world);
};

/// One implicit collider, converted from the public descriptor the way World converts it
/// (world_colliders.cpp, toGpu): unit plane normal, funnel top radius from its angle, c(e) from the
/// restitution, the surface motion as v0 + ω × x.
struct OracleCollider {
  enum class Kind { Plane, BoxInside, BoxOutside, Revolution };
  Kind kind = Kind::Plane;
  Vec3d normal = Vec3d::UnitY();      ///< Plane: unit normal
  double offset = 0.0;                ///< Plane: solid where normal·x < offset, m
  Vec3d center = Vec3d::Zero();       ///< Box: centre; Revolution: base of the axis, m
  Vec3d halfExtents = Vec3d::Zero();  ///< Box, m
  QuatD orientation{};                ///< Box
  /// Revolution: the segment (r0, y0)-(r1, y1) of the (radius, height above base) half-plane.
  double r0 = 0.0, y0 = 0.0, r1 = 0.0, y1 = 0.0;
  double friction = 0.0;       ///< μ against grains
  double dampingFactor = 0.0;  ///< c(e) of the surface's restitution
  /// ColliderMotion as the kernel evaluates it: the surface velocity at x is
  /// velocityAtOrigin + spin × x, with velocityAtOrigin = v - ω × (the reference point). m/s.
  Vec3d velocityAtOrigin = Vec3d::Zero();
  Vec3d spin = Vec3d::Zero();  ///< ω, rad/s

  /// The surface's velocity at the point x (m/s). HertzMindlin only: the paper's law as the GPU
  /// runs it takes the particle's velocity alone against every collider.
  Vec3d surfaceVelocity(const Vec3d& x) const { return velocityAtOrigin + spin.cross(x); }

  static OracleCollider from(const Plane& plane);
  static OracleCollider from(const Box& box);
  static OracleCollider from(const Cylinder& cylinder);
  static OracleCollider from(const Funnel& funnel);
};

/// One surface a particle touches: unit normal towards the particle, overlap ξ > 0 (m), and the
/// face that keys the contact's history (contact_slots.glsl): 0 for a plane, a solid box and a
/// wall of revolution; axis · 2 + (1 on the + side) for a container box's walls.
struct ColliderHit {
  Vec3d normal;
  double overlap;
  std::uint32_t face;
};

/// The surfaces of `c` that a sphere of radius r at p overlaps (colliders.glsl).
std::vector<ColliderHit> colliderHits(const OracleCollider& c, const Vec3d& p, double r);

/// A rigid body in its principal frame.
struct OracleBody {
  Vec3d position = Vec3d::Zero();          ///< centre of mass, m
  QuatD orientation{};                     ///< principal frame to world
  Vec3d velocity = Vec3d::Zero();          ///< m/s
  Vec3d angularVelocity = Vec3d::Zero();   ///< rad/s, world frame
  Vec3d principalInertia = Vec3d::Ones();  ///< kg·m²
  double mass = 1.0;                       ///< kg
  double boundingRadius = 0.0;             ///< m; the rim-speed guard uses it
  Motion motion = Motion::Dynamic;
  std::vector<Vec3d> offsets;  ///< particle centres in the principal frame, m
  QuatD principalRotation{};   ///< the template's principal frame in its original frame
  /// Its BodyId::index in the World. The oracle holds the bodies in the World's slot order, which
  /// a sort of the granules by place makes differ from the ids.
  std::uint32_t id = 0;

  /// A body from a read-back state and the template it was built from. BodyState's orientation
  /// is the template's original frame; the principal frame is that times principalRotation (the
  /// identity for the tetrahedral granule and the single sphere).
  static OracleBody from(const BodyState& state, const ParticleTemplate& shape, Motion motion);
  /// Orientation of the template's original frame, as World::readBodies reports it.
  QuatD templateOrientation() const;
  /// Particle inverse mass as World uploads it (particleLocal.w), 1/kg: for dynamic bodies the
  /// body's 1/M under HertzMindlin (the law shares the bodies' masses among their contacts) and
  /// the particle's share count/M under PaperViscous; 0 for kinematic, -1 for static bodies.
  double particleInverseMass(ContactLaw law) const;
};

/// One particle: world position and velocity and what the contact law needs from its body.
struct OracleParticle {
  std::uint32_t body = 0;
  Vec3d position = Vec3d::Zero();  ///< m
  Vec3d velocity = Vec3d::Zero();  ///< m/s
  Vec3d spin = Vec3d::Zero();      ///< the body's angular velocity, rad/s (HertzMindlin)
  /// As uploaded (OracleBody::particleInverseMass): > 0 dynamic, 0 kinematic, -1 static, 1/kg.
  double inverseMass = 0.0;
};

// --- Contact history (ContactLaw::HertzMindlin) -------------------------------------------

/// Partner keys of contact slots, as contact_slots.glsl writes them: the partner particle's id
/// + 1, or kSlotCollider | collider index · kSlotColliderFaces + face; kSlotEmpty is a free slot.
inline constexpr std::uint32_t kSlotEmpty = 0u;
inline constexpr std::uint32_t kSlotCollider = 0x80000000u;
inline constexpr std::uint32_t kSlotColliderFaces = 8u;
std::uint32_t particleSlotKey(std::size_t particle);
std::uint32_t colliderSlotKey(std::size_t collider, std::uint32_t face);

/// A contact of one particle with one partner (the GPU's slot, without its position in the
/// particle's twelve).
struct ContactKey {
  std::uint32_t particle = 0;  ///< the particle that keeps the slot
  std::uint32_t partner = 0;   ///< slot key (particleSlotKey, colliderSlotKey)
  auto operator<=>(const ContactKey&) const = default;
};

/// What one contact carries from one substep to the next.
struct ContactHistory {
  Vec3d spring = Vec3d::Zero();         ///< tangential displacement δ, m
  Vec3d rollingSpring = Vec3d::Zero();  ///< rolling displacement δ_r (rolling friction), m
  /// n: contacts that joined the two bodies (the partner body, or the collider face) in the
  /// substep that wrote the slot, as the body pass counted them. 0: not counted (a slot that a
  /// restore wrote); the contact law takes it as 1.
  std::uint32_t pairs = 0;
};

using ContactHistoryMap = std::map<ContactKey, ContactHistory>;

/// The history the GPU holds, from WorldSnapshot::contacts (recording.h): every non-empty slot
/// with its spring (float bits in words 0..2, key in word 3) and pair count (slot k in byte
/// k % 4 of pairs[k / 4]); and with rolling friction its rolling spring (WorldSnapshot::rolling).
ContactHistoryMap historyFromSnapshot(const WorldSnapshot& snapshot);

// --- Contact law (contact_law.glsl) -------------------------------------------------------

/// PaperViscous: force of one contact on "this" particle (contactForce, eq. 9 and 10). n points
/// from the other body to this particle, vRel = v_this - v_other, invMassSum = 1/m*.
Vec3d contactForce(double xi, const Vec3d& n, const Vec3d& vRel, double stiffness,
                   double dampingFactor, double invMassSum, double friction,
                   double tangentialDamping);

/// A contact's spring turned with the contact into the plane normal to n (turnedIntoPlane).
Vec3d turnedIntoPlane(const Vec3d& spring, const Vec3d& n);

/// HertzMindlin: one contact's force and its spring after this substep (hertzMindlin).
struct MindlinResult {
  Vec3d force = Vec3d::Zero();            ///< F_n n + F_t on this particle, N
  double normalForce = 0.0;               ///< F_n >= 0, N
  Vec3d tangentialForce = Vec3d::Zero();  ///< F_t, N
  Vec3d spring = Vec3d::Zero();           ///< δ after the substep (to keep), m
  bool slipping = false;                  ///< |F_t| hit the cap μ F_n (and δ was reset)
  double shearStiffness = 0.0;            ///< k_t = k_t0 √ξ, N/m
  double damping = 0.0;                   ///< η, N·s/m
};

/// Rolling friction: one contact's couple and its rolling spring after this substep
/// (rollingResistance).
struct RollingResult {
  Vec3d torque = Vec3d::Zero();  ///< on this particle, N·m
  Vec3d spring = Vec3d::Zero();  ///< δ_r after the substep (to keep), m
  Vec3d force = Vec3d::Zero();   ///< F_r, N (the couple is R n × F_r)
  bool rolls = false;            ///< |F_r| hit the cap μ_r F_n (and δ_r was reset)
};
/// relativeSpin = ω_this - ω_other; contact: the contact's hertzMindlin result this substep;
/// spring = δ_r of the previous substep.
RollingResult rollingResistance(const Vec3d& relativeSpin, const Vec3d& n, double radius,
                                const MindlinResult& contact, double rollingFriction,
                                double timeStep, const Vec3d& spring);
/// n from the other body to this particle; vRel = this body's velocity minus the other's at the
/// contact point; invMassSum = n_pairs (1/M_a + 1/M_b); spring = δ of the previous substep.
MindlinResult hertzMindlin(double xi, const Vec3d& n, const Vec3d& vRel, double stiffness,
                           double shearStiffness, double dampingFactor, double invMassSum,
                           double friction, double timeStep, const Vec3d& spring);

/// One contact as pass 2 sees it from one particle (a particle pair appears twice, once from
/// each side, as in the GPU's gather). The coefficients are the ones the law is applied with.
struct OracleContact {
  static constexpr std::size_t kCollider = ~std::size_t(0);
  ContactLaw law = ContactLaw::HertzMindlin;
  std::size_t particle = 0;          ///< the particle the force acts on
  std::size_t other = kCollider;     ///< the other particle, or kCollider
  std::size_t collider = kCollider;  ///< collider index (ColliderId::index), or kCollider
  std::uint32_t key = kSlotEmpty;    ///< HertzMindlin: the slot key of the partner
  Vec3d normal = Vec3d::Zero();      ///< unit, from the other body (or the surface) to `particle`
  double overlap = 0.0;              ///< ξ (PaperViscous: after the guard), m
  Vec3d lever = Vec3d::Zero();       ///< HertzMindlin: contact point - particle centre, m
  Vec3d relativeVelocity = Vec3d::Zero();  ///< at the contact point (Paper: centres), m/s
  /// For round-off estimates: the sum of the magnitudes of the terms relativeVelocity is made of
  /// (each body's velocity and spin term, the collider's surface velocity), m/s, and of the
  /// spins that act across the contact point, rad/s.
  double velocityTerms = 0.0;
  double spinTerms = 0.0;
  double stiffness = 0.0;       ///< k_n, N/m^{3/2}
  double shearStiffness = 0.0;  ///< HertzMindlin: k_t0, N/m^{3/2}
  /// c(e); HertzMindlin: 0 for a contact that is new this substep (no history).
  double dampingFactor = 0.0;
  double invMassSum = 0.0;         ///< 1/m*, 1/kg (HertzMindlin: n_pairs (1/M_a + 1/M_b))
  double friction = 0.0;           ///< μ
  double tangentialDamping = 0.0;  ///< PaperViscous: γ_s, N·s/m
  double timeStep = 0.0;           ///< HertzMindlin: the spring advances by v_t dt, s
  /// HertzMindlin with rolling friction: the bodies' spin minus the partner's (the collider's),
  /// rad/s; the effective rolling radius R, m; μ_r.
  Vec3d relativeSpin = Vec3d::Zero();
  double rollingRadius = 0.0;
  double rollingFriction = 0.0;
  bool fresh = true;                    ///< HertzMindlin: no history from the previous substep
  std::uint32_t pairs = 0;              ///< HertzMindlin: n_pairs applied (1 when fresh)
  Vec3d spring = Vec3d::Zero();         ///< HertzMindlin: δ of the previous substep, m
  Vec3d rollingSpring = Vec3d::Zero();  ///< rolling friction: δ_r of the previous substep, m

  /// The law applied to this contact: the force on `particle` and (HertzMindlin) its new spring.
  MindlinResult evaluate() const;
  Vec3d force() const { return evaluate().force; }
  /// Rolling friction's couple on `particle` and its new rolling spring, for this substep's
  /// result r of the law (nothing under PaperViscous or without rolling friction).
  RollingResult rolling(const MindlinResult& r) const;
  /// Torque about the particle's centre, N·m: the force's, and rolling friction's couple.
  Vec3d torque() const {
    const MindlinResult r = evaluate();
    return lever.cross(r.force) + rolling(r).torque;
  }
};

/// Tallies of the HertzMindlin contacts the oracle has applied (contact-substeps), to show
/// that a scene exercises each state.
struct ContactTally {
  std::uint64_t fresh = 0;     ///< first substep of a contact (undamped)
  std::uint64_t sticking = 0;  ///< with history, |F_t| below μ F_n
  std::uint64_t slipping = 0;  ///< with history, capped at μ F_n
};

/// What pass 2 writes: per particle the contact force (no gravity) and the torque about its
/// centre, and (HertzMindlin) the contact history of this substep, pair counts not yet taken.
struct ContactPass {
  std::vector<Vec3d> force;   ///< N
  std::vector<Vec3d> torque;  ///< N·m
  ContactHistoryMap history;
  std::vector<ContactTally> tally;  ///< of this substep, per body (of the particle)
};

/// The whole system: bodies, colliders, the model and the contact history; steps like
/// World::substep.
class CpuOracle {
 public:
  /// `colliders` in the order they were added to the World (the index keys their contacts);
  /// `history` as the GPU holds it (historyFromSnapshot), empty for a World that never stepped.
  CpuOracle(const OracleModel& model, std::vector<OracleBody> bodies,
            std::vector<OracleCollider> colliders, ContactHistoryMap history = {});

  /// Pass 1 (eq. 7, 8): every particle's world position and velocity, in body order.
  std::vector<OracleParticle> particlesFromBodies() const;
  /// Pass 2, geometry: every contact of every particle with particles of other bodies (closer
  /// than one diameter) and with the colliders, with its history. Takes the particles as input
  /// so that a test can feed the GPU's own particle state.
  std::vector<OracleContact> findContacts(const std::vector<OracleParticle>& particles) const;
  /// Pass 2, forces: the contact law on every contact of findContacts.
  ContactPass contactPass(const std::vector<OracleParticle>& particles) const;
  /// One substep: passes 1, 2 and 3 (eq. 2-6), then the pair counts of the new history.
  void step();
  void step(int count);
  /// Passes 2 and 3 from the given particle state in place of pass 1 (a test feeds the GPU's).
  void step(const std::vector<OracleParticle>& particles);

  const std::vector<OracleBody>& bodies() const { return m_bodies; }
  const ContactHistoryMap& history() const { return m_history; }
  /// Body b's contacts (those its particles keep), summed over every step() since construction.
  const ContactTally& tally(std::size_t body) const { return m_tally[body]; }
  /// The body that owns particle i.
  std::uint32_t particleBody(std::size_t i) const { return m_particleBody[i]; }
  const OracleModel& model() const { return m_model; }
  const std::vector<OracleCollider>& colliders() const { return m_colliders; }
  /// Mutable, so that a test can run a deliberately wrong model (the comparison must notice).
  OracleModel& model() { return m_model; }
  std::vector<OracleCollider>& colliders() { return m_colliders; }

 private:
  void integrate(const std::vector<OracleParticle>& particles, const ContactPass& pass);
  /// The body passes' count (contact_pairs.glsl): for each body and each of its particles'
  /// contacts, the number of the body's contacts that name the same partner (the partner
  /// particle's body, or the collider face).
  void countPairs(ContactHistoryMap& history) const;

  OracleModel m_model;
  std::vector<OracleBody> m_bodies;
  std::vector<OracleCollider> m_colliders;
  std::vector<std::uint32_t> m_particleBody;
  ContactHistoryMap m_history;
  std::vector<ContactTally> m_tally;  // per body
};

}  // namespace sandphys::oracle
