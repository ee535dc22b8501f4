#include "oracle/cpu_oracle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

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
  m.law = c.law;
  m.radius = c.radius;
  m.diameter = s.particleDiameter;
  m.maxOverlap = c.maxOverlap;  // +infinity under HertzMindlin
  m.stiffnessGrain = c.stiffnessGrain;
  m.stiffnessWall = c.stiffnessWall;
  m.shearStiffnessGrain = c.shearStiffnessGrain;
  m.shearStiffnessWall = c.shearStiffnessWall;
  m.dampingFactorGrain = c.dampingFactorGrain;
  m.friction = s.material.friction;
  m.rollingFriction = s.material.rollingFriction;
  m.tangentialDamping = c.tangentialDamping;
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

// The surface motion as World uploads it (setMotion): v0 = v - ω × reference, so that the
// surface velocity at x is v0 + ω × x.
void setMotion(OracleCollider& c, const ColliderMotion& motion, const Vec3d& reference) {
  c.spin = toDouble(motion.angularVelocity);
  c.velocityAtOrigin = toDouble(motion.velocity) - c.spin.cross(reference);
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
  setMotion(c, p.motion, c.offset * c.normal);  // the plane's point nearest the origin
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
  setMotion(c, b.motion, c.center);
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
  setMotion(c, cyl.motion, c.center);
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
  setMotion(c, f.motion, c.center);
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
  b.id = state.id.index;
  return b;
}

QuatD OracleBody::templateOrientation() const {
  const QuatD& p = principalRotation;
  return multiply(orientation, {p.w, -p.x, -p.y, -p.z});
}

double OracleBody::particleInverseMass(ContactLaw law) const {
  if (motion == Motion::Static) return -1.0;
  if (motion == Motion::Kinematic) return 0.0;
  return law == ContactLaw::HertzMindlin ? 1.0 / mass : double(offsets.size()) / mass;
}

// --- Colliders (colliders.glsl) -------------------------------------------------------------

std::vector<ColliderHit> colliderHits(const OracleCollider& c, const Vec3d& p, double r) {
  std::vector<ColliderHit> hits;
  switch (c.kind) {
    case OracleCollider::Kind::Plane: {
      const double xi = r - (c.normal.dot(p) - c.offset);
      if (xi > 0.0) hits.push_back({c.normal, xi, 0u});
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
        // Face: the wall's axis and side (boxFace).
        const auto face = std::uint32_t(axis) * 2u;
        if (toMax < toMin) {
          if (r - toMax > 0.0)
            hits.push_back({rotate(c.orientation, -axisDir), r - toMax, face + 1u});
        } else {
          if (r - toMin > 0.0) hits.push_back({rotate(c.orientation, axisDir), r - toMin, face});
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
        if (r - dist > 0.0) hits.push_back({rotate(c.orientation, delta / dist), r - dist, 0u});
        break;
      }
      const Vec3d depth = c.halfExtents - local.cwiseAbs();
      const int axis =
          depth.x() < depth.y() ? (depth.x() < depth.z() ? 0 : 2) : (depth.y() < depth.z() ? 1 : 2);
      Vec3d normal = Vec3d::Zero();
      normal[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
      hits.push_back({rotate(c.orientation, normal), r + depth[axis], 0u});
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
      hits.push_back({Vec3d(n2.x() * dirX, n2.y(), n2.x() * dirZ), r - dist, 0u});
      break;
    }
  }
  return hits;
}

// --- Contact history (contact_slots.glsl) --------------------------------------------------

std::uint32_t particleSlotKey(std::size_t particle) {
  return std::uint32_t(particle) + 1u;
}

std::uint32_t colliderSlotKey(std::size_t collider, std::uint32_t face) {
  return kSlotCollider | (std::uint32_t(collider) * kSlotColliderFaces + face);
}

ContactHistoryMap historyFromSnapshot(const WorldSnapshot& snapshot) {
  ContactHistoryMap history;
  const auto toVec = [](const auto& words) {
    return Vec3d(std::bit_cast<float>(words[0]), std::bit_cast<float>(words[1]),
                 std::bit_cast<float>(words[2]));
  };
  for (std::size_t i = 0; i < snapshot.contacts.size(); ++i) {
    const StoredContacts& stored = snapshot.contacts[i];
    for (std::size_t k = 0; k < stored.slots.size(); ++k) {
      const std::array<std::uint32_t, 4>& slot = stored.slots[k];
      if (slot[3] == kSlotEmpty) continue;
      ContactHistory h;
      h.spring = toVec(slot);
      if (i < snapshot.rolling.size()) h.rollingSpring = toVec(snapshot.rolling[i].springs[k]);
      h.pairs = (stored.pairs[k / 4] >> (8u * (k % 4))) & 0xffu;
      history[{std::uint32_t(i), slot[3]}] = h;
    }
  }
  return history;
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

Vec3d turnedIntoPlane(const Vec3d& spring, const Vec3d& n) {
  // Its normal part dropped, its length kept.
  const Vec3d planar = spring - spring.dot(n) * n;
  return planar.norm() > 0.0 ? Vec3d(planar * (spring.norm() / planar.norm()))
                             : Vec3d(Vec3d::Zero());
}

MindlinResult hertzMindlin(double xi, const Vec3d& n, const Vec3d& vRel, double stiffness,
                           double shearStiffness, double dampingFactor, double invMassSum,
                           double friction, double timeStep, const Vec3d& spring) {
  // Not the paper's (docs/architecture.md, "contacts"): LAMMPS pair granular with hertz/material,
  // damping tsuji and tangential mindlin, in hertzMindlin's order of operations.
  // Normal: F_n = k_n ξ^{3/2} + η ξ', η = c(e) sqrt(m* k_n) ξ^{1/4} (Tsuji), never pulling.
  const double eta = dampingFactor * std::sqrt(stiffness / invMassSum) * std::pow(xi, 0.25);
  const double xiDot = -vRel.dot(n);  // approach speed
  MindlinResult r;
  r.normalForce = std::max(stiffness * std::pow(xi, 1.5) + eta * xiDot, 0.0);
  const Vec3d vt = vRel + xiDot * n;  // tangential part of vRel

  // The spring turns with the contact, then stretches by the tangential motion of this substep.
  Vec3d delta = turnedIntoPlane(spring, n) + vt * timeStep;

  // Mindlin: F_t = -k_t δ - η v_t, k_t = k_t0 √ξ; Coulomb caps |F_t| at μ F_n, and a slipping
  // contact's spring is reset to the one that gives the capped force.
  const double kt = shearStiffness * std::sqrt(xi);
  Vec3d ft = -kt * delta - eta * vt;
  const double cap = friction * r.normalForce;
  if (ft.norm() > cap) {
    ft *= cap / ft.norm();
    delta = -(ft + eta * vt) / kt;
    r.slipping = true;
  }
  r.tangentialForce = ft;
  r.spring = delta;
  r.force = r.normalForce * n + ft;
  r.shearStiffness = kt;
  r.damping = eta;
  return r;
}

RollingResult rollingResistance(const Vec3d& relativeSpin, const Vec3d& n, double radius,
                                const MindlinResult& contact, double rollingFriction,
                                double timeStep, const Vec3d& spring) {
  // LAMMPS pair granular's rolling sds, with the tangential spring's k_t and η: the rolling
  // velocity v_r = R (ω × n) stretches a spring that turns with the contact as δ does;
  // F_r = -k_t δ_r - η v_r, capped at μ_r F_n (the spring then reset to the capped force); the
  // couple is R n × F_r.
  const Vec3d vr = radius * relativeSpin.cross(n);
  Vec3d delta = turnedIntoPlane(spring, n) + vr * timeStep;
  RollingResult r;
  r.force = -contact.shearStiffness * delta - contact.damping * vr;
  const double cap = rollingFriction * contact.normalForce;
  if (r.force.norm() > cap) {
    r.force *= cap / r.force.norm();
    delta = -(r.force + contact.damping * vr) / contact.shearStiffness;
    r.rolls = true;
  }
  r.spring = delta;
  r.torque = radius * n.cross(r.force);
  return r;
}

MindlinResult OracleContact::evaluate() const {
  if (law == ContactLaw::HertzMindlin) {
    return hertzMindlin(overlap, normal, relativeVelocity, stiffness, shearStiffness, dampingFactor,
                        invMassSum, friction, timeStep, spring);
  }
  MindlinResult r;
  r.force = contactForce(overlap, normal, relativeVelocity, stiffness, dampingFactor, invMassSum,
                         friction, tangentialDamping);
  r.normalForce = r.force.dot(normal);
  r.tangentialForce = r.force - r.normalForce * normal;
  return r;
}

RollingResult OracleContact::rolling(const MindlinResult& r) const {
  if (law != ContactLaw::HertzMindlin || rollingFriction == 0.0) return {};
  return rollingResistance(relativeSpin, normal, rollingRadius, r, rollingFriction, timeStep,
                           rollingSpring);
}

// --- The step -------------------------------------------------------------------------------

CpuOracle::CpuOracle(const OracleModel& model, std::vector<OracleBody> bodies,
                     std::vector<OracleCollider> colliders, ContactHistoryMap history)
    : m_model(model),
      m_bodies(std::move(bodies)),
      m_colliders(std::move(colliders)),
      m_history(std::move(history)) {
  for (std::uint32_t b = 0; b < m_bodies.size(); ++b) {
    m_particleBody.insert(m_particleBody.end(), m_bodies[b].offsets.size(), b);
  }
  m_tally.resize(m_bodies.size());
}

std::vector<OracleParticle> CpuOracle::particlesFromBodies() const {
  std::vector<OracleParticle> particles;
  for (std::uint32_t b = 0; b < m_bodies.size(); ++b) {
    const OracleBody& body = m_bodies[b];
    for (const Vec3d& offset : body.offsets) {
      // Eq. 7: x_i = x_body + R r_i; eq. 8: v_i = v_body + ω × (R r_i).
      const Vec3d r = rotate(body.orientation, offset);
      particles.push_back({b, body.position + r, body.velocity + body.angularVelocity.cross(r),
                           body.angularVelocity, body.particleInverseMass(m_model.law)});
    }
  }
  return particles;
}

std::vector<OracleContact> CpuOracle::findContacts(
    const std::vector<OracleParticle>& particles) const {
  const OracleModel& m = m_model;
  const bool mindlin = m.law == ContactLaw::HertzMindlin;
  // HertzMindlin: the contact's history from the previous substep. A contact found there has
  // its spring and pair count n (a count of 0 counts as 1); a new one starts from a zero spring
  // with n = 1 and no damping for this substep (contacts.comp, mindlinContact).
  auto withHistory = [&](OracleContact c) {
    if (!mindlin) return c;
    const auto it = m_history.find({std::uint32_t(c.particle), c.key});
    c.fresh = it == m_history.end();
    c.pairs = c.fresh ? 1u : std::max(it->second.pairs, 1u);
    c.spring = c.fresh ? Vec3d(Vec3d::Zero()) : it->second.spring;
    c.rollingSpring = c.fresh ? Vec3d(Vec3d::Zero()) : it->second.rollingSpring;
    if (c.fresh) c.dampingFactor = 0.0;
    c.invMassSum *= double(c.pairs);
    return c;
  };
  std::vector<OracleContact> contacts;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const OracleParticle& self = particles[i];
    // Static particles (rough floors) never move: the GPU skips them and writes no force.
    if (self.inverseMass < 0.0) continue;
    // Every particle of every other body closer than one diameter.
    for (std::size_t j = 0; j < particles.size(); ++j) {
      const OracleParticle& other = particles[j];
      if (other.body == self.body) continue;
      const Vec3d d = self.position - other.position;
      const double dist = d.norm();
      if (dist >= m.diameter || dist == 0.0) continue;
      const double invMassSum = std::max(self.inverseMass, 0.0) + std::max(other.inverseMass, 0.0);
      if (invMassSum == 0.0) continue;  // two immovable bodies
      const Vec3d n = d / dist;
      if (!mindlin) {
        contacts.push_back({.law = m.law,
                            .particle = i,
                            .other = j,
                            .normal = n,
                            .overlap = std::min(m.diameter - dist, m.maxOverlap),  // guard: d/10
                            .relativeVelocity = self.velocity - other.velocity,
                            .velocityTerms = self.velocity.norm() + other.velocity.norm(),
                            .stiffness = m.stiffnessGrain,
                            .dampingFactor = m.dampingFactorGrain,
                            .invMassSum = invMassSum,
                            .friction = m.friction,
                            .tangentialDamping = m.tangentialDamping});
        continue;
      }
      // The contact point is the midpoint of the two centres; the relative velocity there
      // includes both bodies' spins.
      const Vec3d point = 0.5 * (self.position + other.position);
      const Vec3d selfSpinTerm = self.spin.cross(point - self.position);
      const Vec3d otherSpinTerm = other.spin.cross(point - other.position);
      contacts.push_back(withHistory(
          {.law = m.law,
           .particle = i,
           .other = j,
           .key = particleSlotKey(j),
           .normal = n,
           .overlap = m.diameter - dist,
           .lever = point - self.position,
           .relativeVelocity = (self.velocity + selfSpinTerm) - (other.velocity + otherSpinTerm),
           .velocityTerms = self.velocity.norm() + selfSpinTerm.norm() + other.velocity.norm() +
                            otherSpinTerm.norm(),
           .spinTerms = self.spin.norm() + other.spin.norm(),
           .stiffness = m.stiffnessGrain,
           .shearStiffness = m.shearStiffnessGrain,
           .dampingFactor = m.dampingFactorGrain,
           .invMassSum = invMassSum,
           .friction = m.friction,
           .timeStep = m.timeStep,
           .relativeSpin = self.spin - other.spin,
           .rollingRadius = 0.25 * m.diameter,
           .rollingFriction = m.rollingFriction}));
    }
    // Colliders are rigid and immovable: m* is the particle's own mass (PaperViscous) or its
    // body's (HertzMindlin), k_n the wall stiffness, and only particles of dynamic bodies feel
    // them.
    if (self.inverseMass <= 0.0) continue;
    for (std::size_t k = 0; k < m_colliders.size(); ++k) {
      const OracleCollider& c = m_colliders[k];
      for (const ColliderHit& hit : colliderHits(c, self.position, m.radius)) {
        if (!mindlin) {
          // The paper's law acts at the particle's centre: the surface's velocity there.
          const Vec3d surface = c.surfaceVelocity(self.position);
          contacts.push_back({.law = m.law,
                              .particle = i,
                              .collider = k,
                              .normal = hit.normal,
                              .overlap = std::min(hit.overlap, m.maxOverlap),
                              .relativeVelocity = self.velocity - surface,
                              .velocityTerms = self.velocity.norm() + c.velocityAtOrigin.norm() +
                                               c.spin.cross(self.position).norm(),
                              .stiffness = m.stiffnessWall,
                              .dampingFactor = c.dampingFactor,
                              .invMassSum = self.inverseMass,
                              .friction = c.friction,
                              .tangentialDamping = m.tangentialDamping});
          continue;
        }
        // The contact point is the middle of the overlap; the surface moves there with the
        // collider's motion.
        const Vec3d point = self.position - hit.normal * (m.radius - 0.5 * hit.overlap);
        const Vec3d spinTerm = self.spin.cross(point - self.position);
        const Vec3d surface = c.surfaceVelocity(point);
        contacts.push_back(
            withHistory({.law = m.law,
                         .particle = i,
                         .collider = k,
                         .key = colliderSlotKey(k, hit.face),
                         .normal = hit.normal,
                         .overlap = hit.overlap,
                         .lever = point - self.position,
                         .relativeVelocity = (self.velocity + spinTerm) - surface,
                         .velocityTerms = self.velocity.norm() + spinTerm.norm() +
                                          c.velocityAtOrigin.norm() + c.spin.cross(point).norm(),
                         .spinTerms = self.spin.norm() + c.spin.norm(),
                         .stiffness = m.stiffnessWall,
                         .shearStiffness = m.shearStiffnessWall,
                         .dampingFactor = c.dampingFactor,
                         .invMassSum = self.inverseMass,
                         .friction = c.friction,
                         .timeStep = m.timeStep,
                         .relativeSpin = self.spin - c.spin,
                         .rollingRadius = m.radius,
                         .rollingFriction = m.rollingFriction}));
      }
    }
  }
  return contacts;
}

ContactPass CpuOracle::contactPass(const std::vector<OracleParticle>& particles) const {
  ContactPass pass;
  pass.force.assign(particles.size(), Vec3d::Zero());
  pass.torque.assign(particles.size(), Vec3d::Zero());
  pass.tally.resize(m_bodies.size());
  for (const OracleContact& c : findContacts(particles)) {
    const MindlinResult r = c.evaluate();
    pass.force[c.particle] += r.force;
    if (c.law != ContactLaw::HertzMindlin) continue;
    // Friction acts at the contact point: a torque about the particle's centre; and rolling
    // friction's couple.
    const RollingResult rolling = c.rolling(r);
    pass.torque[c.particle] += c.lever.cross(r.force) + rolling.torque;
    pass.history[{std::uint32_t(c.particle), c.key}] = {r.spring, rolling.spring, 0u};
    ContactTally& tally = pass.tally[particles[c.particle].body];
    ++(c.fresh ? tally.fresh : r.slipping ? tally.slipping : tally.sticking);
  }
  return pass;
}

void CpuOracle::integrate(const std::vector<OracleParticle>& particles, const ContactPass& pass) {
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
      // position (from pass 1) minus the body's position before this step; HertzMindlin adds
      // each particle's torque of friction at its contact points.
      Vec3d force = Vec3d::Zero();
      Vec3d torque = Vec3d::Zero();
      for (std::size_t k = first; k < first + count; ++k) {
        force += pass.force[k];
        torque += (particles[k].position - body.position).cross(pass.force[k]) + pass.torque[k];
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

void CpuOracle::countPairs(ContactHistoryMap& history) const {
  // The partner a slot names: a collider key itself (bit 31 set, never a body index), else the
  // owning body of the partner particle.
  auto partner = [&](std::uint32_t key) {
    return (key & kSlotCollider) != 0u ? key : m_particleBody[key - 1u];
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> count;  // (body, partner)
  for (const auto& [key, h] : history)
    ++count[{m_particleBody[key.particle], partner(key.partner)}];
  for (auto& [key, h] : history)
    h.pairs = count[{m_particleBody[key.particle], partner(key.partner)}];
}

void CpuOracle::step(const std::vector<OracleParticle>& particles) {
  ContactPass pass = contactPass(particles);
  integrate(particles, pass);
  if (m_model.law == ContactLaw::HertzMindlin) {
    countPairs(pass.history);
    m_history = std::move(pass.history);
    for (std::size_t b = 0; b < m_tally.size(); ++b) {
      m_tally[b].fresh += pass.tally[b].fresh;
      m_tally[b].sticking += pass.tally[b].sticking;
      m_tally[b].slipping += pass.tally[b].slipping;
    }
  }
}

void CpuOracle::step() {
  step(particlesFromBodies());
}

void CpuOracle::step(int count) {
  for (int i = 0; i < count; ++i) step();
}

}  // namespace sandphys::oracle
