#pragma once

// A readable double-precision CPU oracle of exactly the model the GPU step runs (shaders/sim/):
// plain O(n²) loops, no grid, no float. It exists so that the oracle tests can tell a real model
// difference in the kernels (a wrong sign, a missing term, a missed neighbour) from float
// round-off. One step mirrors World's substep pass by pass:
//   1. particles from bodies          (eq. 7, 8)           bodies_to_particles.comp
//   2. contact and collider forces    (eq. 9, 10)          contacts.comp, contact_law.glsl,
//                                                          colliders.glsl
//   3. body sums and integration      (eq. 2-6)            integrate_bodies.comp
// Left out: sinks and emitters (no oracle scene uses them), and the grid by design: the O(n²)
// search finds every neighbour that the GPU's hashed gather should find.

#include <Eigen/Dense>

#include <cstddef>
#include <cstdint>
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
  double radius = 0.0;              ///< particle radius r, m
  double diameter = 0.0;            ///< particle diameter d = contact distance, m
  double maxOverlap = 0.0;          ///< penetration guard ξ_max = d/10, m
  double stiffnessGrain = 0.0;      ///< k_n grain-grain, N/m^{3/2}
  double dampingFactorGrain = 0.0;  ///< c(e) grain-grain, dimensionless
  double friction = 0.0;            ///< μ grain-grain
  double tangentialDamping = 0.0;   ///< γ_s, N·s/m (grain-grain and grain-collider)
  double stiffnessWall = 0.0;       ///< k_n grain-collider, N/m^{3/2}
  double timeStep = 0.0;            ///< s
  double maxSpeed = 0.0;            ///< speed guard, m/s
  Vec3d gravity = Vec3d::Zero();    ///< m/s²

  static OracleModel fromWorld(const World& world);
};

/// One implicit collider, converted from the public descriptor the way World converts it
/// (world.cpp, toGpu): unit plane normal, funnel top radius from its angle, c(e) from the
/// restitution.
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

  static OracleCollider from(const Plane& plane);
  static OracleCollider from(const Box& box);
  static OracleCollider from(const Cylinder& cylinder);
  static OracleCollider from(const Funnel& funnel);
};

/// One surface a particle touches: unit normal towards the particle, overlap ξ > 0 (m).
struct ColliderHit {
  Vec3d normal;
  double overlap;
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

  /// A body from a read-back state and the template it was built from. BodyState's orientation
  /// is the template's original frame; the principal frame is that times principalRotation (the
  /// identity for the tetrahedral granule and the single sphere).
  static OracleBody from(const BodyState& state, const ParticleTemplate& shape, Motion motion);
  /// Orientation of the template's original frame, as World::readBodies reports it.
  QuatD templateOrientation() const;
  /// Particle inverse mass as World uploads it: count / mass for dynamic bodies, 0 otherwise.
  double particleInverseMass() const;
};

/// One particle: world position and velocity and what the contact law needs from its body.
struct OracleParticle {
  std::uint32_t body = 0;
  Vec3d position = Vec3d::Zero();  ///< m
  Vec3d velocity = Vec3d::Zero();  ///< m/s
  double inverseMass = 0.0;        ///< 1/kg; 0 for static and kinematic bodies
};

/// Force of one contact on "this" particle (contact_law.glsl, eq. 9 and 10). n points from the
/// other body to this particle, vRel = v_this - v_other, invMassSum = 1/m*.
Vec3d contactForce(double xi, const Vec3d& n, const Vec3d& vRel, double stiffness,
                   double dampingFactor, double invMassSum, double friction,
                   double tangentialDamping);

/// One contact as pass 2 sees it from one particle (a particle pair appears twice, once from
/// each side, as in the GPU's gather).
struct OracleContact {
  std::size_t particle = 0;       ///< the particle the force acts on
  std::size_t other = kCollider;  ///< the other particle, or kCollider
  Vec3d normal = Vec3d::Zero();   ///< unit, from the other body (or the surface) to `particle`
  double overlap = 0.0;           ///< ξ after the penetration guard, m
  Vec3d relativeVelocity = Vec3d::Zero();  ///< v_particle - v_other, m/s
  double stiffness = 0.0;                  ///< k_n, N/m^{3/2}
  double dampingFactor = 0.0;              ///< c(e)
  double invMassSum = 0.0;                 ///< 1/m*, 1/kg
  double friction = 0.0;                   ///< μ
  double tangentialDamping = 0.0;          ///< γ_s, N·s/m
  static constexpr std::size_t kCollider = ~std::size_t(0);

  /// The contact law applied to this contact (eq. 9, 10).
  Vec3d force() const;
};

/// The whole system: bodies, colliders and the model; steps like World::substep.
class CpuOracle {
 public:
  CpuOracle(const OracleModel& model, std::vector<OracleBody> bodies,
            std::vector<OracleCollider> colliders);

  /// Pass 1 (eq. 7, 8): every particle's world position and velocity, in body order.
  std::vector<OracleParticle> particlesFromBodies() const;
  /// Pass 2, geometry: every contact of every particle with particles of other bodies (closer
  /// than one diameter) and with the colliders. Takes the particles as input so that a test can
  /// feed the GPU's own particle state.
  std::vector<OracleContact> findContacts(const std::vector<OracleParticle>& particles) const;
  /// Pass 2, forces (eq. 9, 10): the contact + collider force on every particle (no gravity), N.
  std::vector<Vec3d> particleForces(const std::vector<OracleParticle>& particles) const;
  /// One substep: passes 1, 2 and 3 (eq. 2-6).
  void step();
  void step(int count);

  const std::vector<OracleBody>& bodies() const { return m_bodies; }
  /// Mutable, so that a test can run a deliberately wrong model (the comparison must notice).
  OracleModel& model() { return m_model; }
  std::vector<OracleCollider>& colliders() { return m_colliders; }

 private:
  void integrate(const std::vector<OracleParticle>& particles, const std::vector<Vec3d>& forces);

  OracleModel m_model;
  std::vector<OracleBody> m_bodies;
  std::vector<OracleCollider> m_colliders;
};

}  // namespace sandphys::oracle
