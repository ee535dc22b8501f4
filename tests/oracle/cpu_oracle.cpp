#include "oracle/cpu_oracle.h"

#include <algorithm>
#include <cmath>

namespace sandphys::oracle {

Vec3d toDouble(Vec3 v) {
  return {v.x, v.y, v.z};
}
QuatD toDouble(Quat q) {
  return {q.w, q.x, q.y, q.z};
}

Vec3d rotate(const QuatD& q, const Vec3d& v) {
  // v' = v + 2w (u × v) + 2 u × (u × v), u = (x, y, z): the same identity as quaternion.glsl.
  const Vec3d u(q.x, q.y, q.z);
  const Vec3d t = 2.0 * u.cross(v);
  return v + q.w * t + u.cross(t);
}

Vec3d rotateInverse(const QuatD& q, const Vec3d& v) {
  return rotate({q.w, -q.x, -q.y, -q.z}, v);
}

QuatD multiply(const QuatD& a, const QuatD& b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// --- Model and scene ------------------------------------------------------------------------

OracleModel OracleModel::fromWorld(const World& world) {
  const ContactModel& c = world.contactModel();
  const WorldSettings& s = world.settings();
  OracleModel m;
  m.radius = c.radius;
  m.diameter = s.particleDiameter;
  m.maxOverlap = c.maxOverlap;
  m.stiffnessGrain = c.stiffnessGrain;
  m.dampingFactorGrain = c.dampingFactorGrain;
  m.friction = s.material.friction;
  m.tangentialDamping = c.tangentialDamping;
  m.stiffnessWall = c.stiffnessWall;
  m.timeStep = c.timeStep;
  m.maxSpeed = s.maxSpeed;
  m.gravity = toDouble(s.gravity);
  return m;
}

namespace {

// The damping factor exactly as World uploads it: c(e) rounded to float.
double surfaceDamping(const SurfaceMaterial& m) {
  return float(hertzDampingFactor(m.restitution));
}

}  // namespace

OracleCollider OracleCollider::from(const Plane& p) {
  OracleCollider c;
  c.kind = Kind::Plane;
  const Vec3d n = toDouble(p.normal);
  // dot(n/|n|, x) < offset/|n| is the same half-space.
  c.normal = n / n.norm();
  c.offset = p.offset / n.norm();
  c.friction = p.material.friction;
  c.dampingFactor = surfaceDamping(p.material);
  return c;
}

OracleCollider OracleCollider::from(const Box& b) {
  OracleCollider c;
  c.kind = b.inside ? Kind::BoxInside : Kind::BoxOutside;
  c.center = toDouble(b.center);
  c.halfExtents = toDouble(b.halfExtents);
  QuatD q = toDouble(b.orientation);
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  c.orientation = {q.w / n, q.x / n, q.y / n, q.z / n};
  c.friction = b.material.friction;
  c.dampingFactor = surfaceDamping(b.material);
  return c;
}

OracleCollider OracleCollider::from(const Cylinder& cyl) {
  OracleCollider c;
  c.kind = Kind::Revolution;
  c.center = toDouble(cyl.base);
  c.r0 = cyl.radius;
  c.y0 = 0.0;
  c.r1 = cyl.radius;
  c.y1 = cyl.height;
  c.friction = cyl.material.friction;
  c.dampingFactor = surfaceDamping(cyl.material);
  return c;
}

OracleCollider OracleCollider::from(const Funnel& f) {
  OracleCollider c;
  c.kind = Kind::Revolution;
  c.center = toDouble(f.outletCenter);
  c.r0 = f.outletRadius;
  c.y0 = 0.0;
  c.r1 = f.outletRadius + f.height * std::tan(double(f.halfAngle));
  c.y1 = f.height;
  c.friction = f.material.friction;
  c.dampingFactor = surfaceDamping(f.material);
  return c;
}

OracleBody OracleBody::from(const BodyState& state, const ParticleTemplate& shape, Motion motion) {
  OracleBody b;
  b.position = toDouble(state.position);
  b.orientation = multiply(toDouble(state.orientation), toDouble(shape.principalRotation));
  b.velocity = toDouble(state.velocity);
  b.angularVelocity = toDouble(state.angularVelocity);
  b.principalInertia = toDouble(shape.principalInertia);
  b.mass = shape.mass;
  b.boundingRadius = shape.boundingRadius;
  b.motion = motion;
  for (const Vec3& o : shape.offsets) b.offsets.push_back(toDouble(o));
  b.principalRotation = toDouble(shape.principalRotation);
  return b;
}

QuatD OracleBody::templateOrientation() const {
  const QuatD& p = principalRotation;
  return multiply(orientation, {p.w, -p.x, -p.y, -p.z});
}

double OracleBody::particleInverseMass() const {
  return motion == Motion::Dynamic ? double(offsets.size()) / mass : 0.0;
}

// --- Colliders (colliders.glsl) -------------------------------------------------------------

std::vector<ColliderHit> colliderHits(const OracleCollider& c, const Vec3d& p, double r) {
  std::vector<ColliderHit> hits;
  switch (c.kind) {
    case OracleCollider::Kind::Plane: {
      const double xi = r - (c.normal.dot(p) - c.offset);
      if (xi > 0.0) hits.push_back({c.normal, xi});
      break;
    }
    case OracleCollider::Kind::BoxInside: {
      // A container: per axis, the nearer of the two walls pushes inwards (a corner touches
      // three walls at most).
      const Vec3d local = rotateInverse(c.orientation, p - c.center);
      for (int axis = 0; axis < 3; ++axis) {
        const double toMax = c.halfExtents[axis] - local[axis];
        const double toMin = c.halfExtents[axis] + local[axis];
        Vec3d axisDir = Vec3d::Zero();
        axisDir[axis] = 1.0;
        if (toMax < toMin) {
          if (r - toMax > 0.0) hits.push_back({rotate(c.orientation, -axisDir), r - toMax});
        } else {
          if (r - toMin > 0.0) hits.push_back({rotate(c.orientation, axisDir), r - toMin});
        }
      }
      break;
    }
    case OracleCollider::Kind::BoxOutside: {
      // A solid: away from the nearest point when outside, out of the nearest face when inside.
      const Vec3d local = rotateInverse(c.orientation, p - c.center);
      const Vec3d nearest = local.cwiseMax(-c.halfExtents).cwiseMin(c.halfExtents);
      const Vec3d delta = local - nearest;
      const double dist = delta.norm();
      if (dist > 0.0) {
        if (r - dist > 0.0) hits.push_back({rotate(c.orientation, delta / dist), r - dist});
        break;
      }
      const Vec3d depth = c.halfExtents - local.cwiseAbs();
      const int axis =
          depth.x() < depth.y() ? (depth.x() < depth.z() ? 0 : 2) : (depth.y() < depth.z() ? 1 : 2);
      Vec3d normal = Vec3d::Zero();
      normal[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
      hits.push_back({rotate(c.orientation, normal), r + depth[axis]});
      break;
    }
    case OracleCollider::Kind::Revolution: {
      // Distance in the (radial, height) half-plane to the swept segment.
      const Vec3d rel = p - c.center;
      const double radial = std::hypot(rel.x(), rel.z());
      const Eigen::Vector2d q(radial, rel.y());
      const Eigen::Vector2d s0(c.r0, c.y0);
      const Eigen::Vector2d seg = Eigen::Vector2d(c.r1, c.y1) - s0;
      const double t = std::clamp((q - s0).dot(seg) / seg.dot(seg), 0.0, 1.0);
      const Eigen::Vector2d delta = q - (s0 + t * seg);
      const double dist = delta.norm();
      if (dist >= r) break;
      Eigen::Vector2d n2;
      if (dist > 0.0) {
        n2 = delta / dist;
      } else {
        n2 = Eigen::Vector2d(-seg.y(), seg.x()).normalized();  // on the wall: towards the axis
        if (n2.x() > 0.0) n2 = -n2;
      }
      const double dirX = radial > 0.0 ? rel.x() / radial : 1.0;
      const double dirZ = radial > 0.0 ? rel.z() / radial : 0.0;
      hits.push_back({Vec3d(n2.x() * dirX, n2.y(), n2.x() * dirZ), r - dist});
      break;
    }
  }
  return hits;
}

// --- Contact law (contact_law.glsl) ---------------------------------------------------------

Vec3d contactForce(double xi, const Vec3d& n, const Vec3d& vRel, double stiffness,
                   double dampingFactor, double invMassSum, double friction,
                   double tangentialDamping) {
  // Eq. 9 with the Tsuji exponent: F_n = k_n ξ^{3/2} + c sqrt(m* k_n) ξ^{1/4} ξ', never pulling.
  const double effectiveMass = 1.0 / invMassSum;
  const double xiDot = -vRel.dot(n);  // approach speed
  double fn = stiffness * std::pow(xi, 1.5) +
              dampingFactor * std::sqrt(effectiveMass * stiffness) * std::pow(xi, 0.25) * xiDot;
  fn = std::max(fn, 0.0);
  // Eq. 10: F_s = -min(μ F_n, γ_s |v_s|) v_s/|v_s|, v_s the tangential part of vRel.
  const Vec3d vs = vRel + xiDot * n;
  const double vsLength = vs.norm();
  Vec3d fs = Vec3d::Zero();
  if (vsLength > 0.0) fs = -std::min(friction * fn, tangentialDamping * vsLength) * vs / vsLength;
  return fn * n + fs;
}

Vec3d OracleContact::force() const {
  return contactForce(overlap, normal, relativeVelocity, stiffness, dampingFactor, invMassSum,
                      friction, tangentialDamping);
}

// --- The step -------------------------------------------------------------------------------

CpuOracle::CpuOracle(const OracleModel& model, std::vector<OracleBody> bodies,
                     std::vector<OracleCollider> colliders)
    : m_model(model), m_bodies(std::move(bodies)), m_colliders(std::move(colliders)) {}

std::vector<OracleParticle> CpuOracle::particlesFromBodies() const {
  std::vector<OracleParticle> particles;
  for (std::uint32_t b = 0; b < m_bodies.size(); ++b) {
    const OracleBody& body = m_bodies[b];
    for (const Vec3d& offset : body.offsets) {
      // Eq. 7: x_i = x_body + R r_i; eq. 8: v_i = v_body + ω × (R r_i).
      const Vec3d r = rotate(body.orientation, offset);
      particles.push_back({b, body.position + r, body.velocity + body.angularVelocity.cross(r),
                           body.particleInverseMass()});
    }
  }
  return particles;
}

std::vector<OracleContact> CpuOracle::findContacts(
    const std::vector<OracleParticle>& particles) const {
  const OracleModel& m = m_model;
  std::vector<OracleContact> contacts;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const OracleParticle& self = particles[i];
    // Every particle of every other body closer than one diameter.
    for (std::size_t j = 0; j < particles.size(); ++j) {
      const OracleParticle& other = particles[j];
      if (other.body == self.body) continue;
      const Vec3d d = self.position - other.position;
      const double dist = d.norm();
      if (dist >= m.diameter || dist == 0.0) continue;
      const double invMassSum = self.inverseMass + other.inverseMass;
      if (invMassSum == 0.0) continue;  // two immovable bodies
      contacts.push_back({.particle = i,
                          .other = j,
                          .normal = d / dist,
                          .overlap = std::min(m.diameter - dist, m.maxOverlap),  // guard: d/10
                          .relativeVelocity = self.velocity - other.velocity,
                          .stiffness = m.stiffnessGrain,
                          .dampingFactor = m.dampingFactorGrain,
                          .invMassSum = invMassSum,
                          .friction = m.friction,
                          .tangentialDamping = m.tangentialDamping});
    }
    // Colliders are rigid and immovable: m* is the particle's own mass, k_n the wall stiffness,
    // and only particles of dynamic bodies feel them.
    if (self.inverseMass == 0.0) continue;
    for (const OracleCollider& c : m_colliders) {
      for (const ColliderHit& hit : colliderHits(c, self.position, m.radius)) {
        contacts.push_back({.particle = i,
                            .normal = hit.normal,
                            .overlap = std::min(hit.overlap, m.maxOverlap),
                            .relativeVelocity = self.velocity,
                            .stiffness = m.stiffnessWall,
                            .dampingFactor = c.dampingFactor,
                            .invMassSum = self.inverseMass,
                            .friction = c.friction,
                            .tangentialDamping = m.tangentialDamping});
      }
    }
  }
  return contacts;
}

std::vector<Vec3d> CpuOracle::particleForces(const std::vector<OracleParticle>& particles) const {
  std::vector<Vec3d> forces(particles.size(), Vec3d::Zero());
  for (const OracleContact& c : findContacts(particles)) forces[c.particle] += c.force();
  return forces;
}

void CpuOracle::integrate(const std::vector<OracleParticle>& particles,
                          const std::vector<Vec3d>& forces) {
  const OracleModel& m = m_model;
  const double dt = m.timeStep;
  std::size_t first = 0;
  for (OracleBody& body : m_bodies) {
    const std::size_t count = body.offsets.size();
    if (body.motion == Motion::Static) {
      first += count;
      continue;
    }
    if (body.motion == Motion::Dynamic) {
      // Eq. 2, 3: total force and torque about the centre of mass, with r the particle's
      // position (from pass 1) minus the body's position before this step.
      Vec3d force = Vec3d::Zero();
      Vec3d torque = Vec3d::Zero();
      for (std::size_t k = first; k < first + count; ++k) {
        force += forces[k];
        torque += (particles[k].position - body.position).cross(forces[k]);
      }
      // Semi-implicit Euler: the velocity first (eq. 4) ...
      body.velocity += dt * (force / body.mass + m.gravity);
      // ... and the spin by Euler's equations in the principal frame (eq. 6):
      // I ω' = τ - ω × (I ω).
      const Vec3d& inertia = body.principalInertia;
      Vec3d omegaLocal = rotateInverse(body.orientation, body.angularVelocity);
      const Vec3d torqueLocal = rotateInverse(body.orientation, torque);
      omegaLocal +=
          dt *
          (torqueLocal - omegaLocal.cross(inertia.cwiseProduct(omegaLocal))).cwiseQuotient(inertia);
      body.angularVelocity = rotate(body.orientation, omegaLocal);

      // Speed guard (CFL clamp): body speed and rim speed |ω| · bounding radius.
      const double speed = body.velocity.norm();
      if (speed > m.maxSpeed) body.velocity *= m.maxSpeed / speed;
      const double rimSpeed = body.angularVelocity.norm() * body.boundingRadius;
      if (rimSpeed > m.maxSpeed) body.angularVelocity *= m.maxSpeed / rimSpeed;
    }
    // ... then the pose with the new velocities (kinematic bodies too): eq. 5,
    // q += ½ dt [ω, 0] q, renormalised.
    body.position += dt * body.velocity;
    const QuatD w{0.0, body.angularVelocity.x(), body.angularVelocity.y(),
                  body.angularVelocity.z()};
    const QuatD dq = multiply(w, body.orientation);
    QuatD& q = body.orientation;
    q = {q.w + 0.5 * dt * dq.w, q.x + 0.5 * dt * dq.x, q.y + 0.5 * dt * dq.y,
         q.z + 0.5 * dt * dq.z};
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    q = {q.w / norm, q.x / norm, q.y / norm, q.z / norm};
    first += count;
  }
}

void CpuOracle::step() {
  const std::vector<OracleParticle> particles = particlesFromBodies();
  integrate(particles, particleForces(particles));
}

void CpuOracle::step(int count) {
  for (int i = 0; i < count; ++i) step();
}

}  // namespace sandphys::oracle
