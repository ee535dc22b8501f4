#include "sandphys/bullet/bridge.h"

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "sandphys/bullet/conversions.h"
#include "sandphys/bullet/shape_mesh.h"

namespace sandphys::bullet {

namespace {

std::string format(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(value));
  return text;
}

std::string format(const btVector3& v) {
  return "(" + format(float(v.x())) + ", " + format(float(v.y())) + ", " + format(float(v.z())) +
         ")";
}

}  // namespace

Bridge::Bridge(World& sand, btDiscreteDynamicsWorld& dynamics, const BridgeSettings& settings)
    : m_sand(sand), m_dynamics(dynamics), m_settings(settings) {
  const WorldSettings& s = sand.settings();
  const btVector3 gravity = dynamics.getGravity();
  const btVector3 sandGravity = toBullet(s.gravity);
  if ((gravity - sandGravity).length() > 1e-4f * std::max(sandGravity.length(), btScalar(1))) {
    throw InvalidArgument("Bridge: Bullet's gravity " + format(gravity) +
                          " differs from WorldSettings.gravity " + format(sandGravity) +
                          " (m/s^2); the coupled bodies and the sand would fall differently");
  }
  if (!(settings.couplingStep >= 0.0f) || !std::isfinite(settings.couplingStep)) {
    throw InvalidArgument("BridgeSettings.couplingStep " + format(settings.couplingStep) +
                          ": must be finite and >= 0 s (0 = automatic)");
  }
  if (!(settings.maxCouplingStep > 0.0f) || !std::isfinite(settings.maxCouplingStep)) {
    throw InvalidArgument("BridgeSettings.maxCouplingStep " + format(settings.maxCouplingStep) +
                          ": must be finite and > 0 s");
  }
  m_lastStep = automaticStep();
  const SleepModel& sleep = sand.sleepModel();
  m_wakeAcceleration =
      sleep.enabled ? sleep.wakeAcceleration : kSleepWakeAcceleration * float(sandGravity.length());
}

float Bridge::automaticStep() const {
  if (m_settings.couplingStep > 0.0f) return std::max(m_settings.couplingStep, m_sand.timeStep());
  float fastest = 0.0f;
  for (const Coupled& c : m_coupled) {
    fastest = std::max(fastest, float(c.body->getLinearVelocity().length() +
                                      c.body->getAngularVelocity().length() * c.reach));
  }
  const float d = m_sand.settings().particleDiameter;
  const float step = fastest > 0.0f ? 0.1f * d / fastest : m_settings.maxCouplingStep;
  // Never shorter than one sand substep: an exchange must move the sand.
  return std::clamp(step, m_sand.timeStep(),
                    std::max(m_settings.maxCouplingStep, m_sand.timeStep()));
}

BodyId Bridge::couple(btRigidBody* body, const CouplingOptions& options) {
  if (!body) throw InvalidArgument("Bridge::couple: the body is null");
  const float d = m_sand.settings().particleDiameter;
  return couple(body, shapeMesh(*body->getCollisionShape(), options.maxChordError * d), options);
}

BodyId Bridge::couple(btRigidBody* body, const TriangleMesh& surface,
                      const CouplingOptions& options) {
  if (!body) throw InvalidArgument("Bridge::couple: the body is null");
  if (find(body)) throw InvalidArgument("Bridge::couple: this Bullet body is coupled already");
  const WorldSettings& s = m_sand.settings();
  const float d = s.particleDiameter;
  const bool isStatic = body->getInvMass() == btScalar(0);
  const float granuleMass = tetrahedronTemplate(d, s.material.density).mass;
  const float mass = isStatic ? 0.0f : float(btScalar(1) / body->getInvMass());
  if (!isStatic && mass < kMinMassInGranules * granuleMass) {
    throw InvalidArgument("Bridge::couple: a body of " + format(mass) + " kg is lighter than " +
                          format(kMinMassInGranules) + " sand granules (" +
                          format(kMinMassInGranules * granuleMass) +
                          " kg): the explicit exchange of forces would not be stable for it");
  }

  MeshSampling sampling;
  sampling.spacing = options.spacing;
  sampling.density = s.material.density;
  const SampledMesh sampled = sampleMesh(surface, d, sampling);
  ParticleTemplate shape = sampled.shape;
  if (!isStatic) {
    // Bullet's centre-of-mass frame is principal: its mass and diagonal inertia are the body's,
    // whatever the sampled surface would give.
    const btVector3 inertia = body->getLocalInertia();
    MassProperties massProperties;
    massProperties.mass = mass;
    massProperties.inertia = {
        {{double(inertia.x()), 0, 0}, {0, double(inertia.y()), 0}, {0, 0, double(inertia.z())}}};
    shape = makeBodyTemplate(sampled.centres, massProperties);
  }
  const btTransform& pose = body->getCenterOfMassTransform();
  BodyDesc desc;
  desc.position = toSand(pose.getOrigin());
  desc.orientation = toSand(pose.getRotation());
  desc.velocity = toSand(body->getLinearVelocity());
  desc.angularVelocity = toSand(body->getAngularVelocity());
  desc.motion = isStatic ? Motion::Static : Motion::Kinematic;
  const BodyId id = m_sand.addBody(shape, desc);
  Coupled coupled{body, id, std::uint32_t(shape.offsets.size()),
                  {},   {}, shape.boundingRadius + 0.5f * d};
  coupled.surface = surface;
  coupled.principalRotation = shape.principalRotation;
  if (isStatic) {
    // The sampled template is about the surface's own centre of mass.
    const auto& com = sampled.massProperties.centreOfMass;
    for (Vec3& v : coupled.surface.vertices) v -= Vec3{float(com[0]), float(com[1]), float(com[2])};
  }
  m_coupled.push_back(std::move(coupled));
  m_frameForce.emplace_back();
  m_frameTorque.emplace_back();
  m_lastForce.emplace_back();
  m_lastTorque.emplace_back();
  return id;
}

const Bridge::Coupled* Bridge::find(const btRigidBody* body) const {
  for (const Coupled& c : m_coupled) {
    if (c.body == body) return &c;
  }
  return nullptr;
}

void Bridge::pushPoses() {
  for (std::size_t i = 0; i < m_coupled.size(); ++i) {
    Coupled& c = m_coupled[i];
    if (c.body->getInvMass() == btScalar(0)) continue;  // static on both sides
    const bool asleep = !c.body->isActive();
    if (asleep && c.asleep) continue;  // pushed at rest when it fell asleep
    if (asleep) {
      c.restForce = m_lastForce[i];
      c.restTorque = m_lastTorque[i];
    }
    c.asleep = asleep;
    const btTransform& pose = c.body->getCenterOfMassTransform();
    const BodyDesc state{.position = toSand(pose.getOrigin()),
                         .orientation = toSand(pose.getRotation()),
                         .velocity = asleep ? Vec3{} : toSand(c.body->getLinearVelocity()),
                         .angularVelocity = asleep ? Vec3{} : toSand(c.body->getAngularVelocity()),
                         .motion = Motion::Kinematic};
    m_sand.setBodyState(c.sandBody, state);
    m_pushes.push_back({c.sandBody.index, state});
  }
}

void Bridge::applySandForces(double weight) {
  const std::vector<BodyForce> forces = m_sand.takeBodyForces();
  for (std::size_t i = 0; i < m_coupled.size(); ++i) {
    Coupled& c = m_coupled[i];
    if (c.body->getInvMass() == btScalar(0)) continue;
    for (const BodyForce& f : forces) {
      if (!(f.body == c.sandBody)) continue;
      // A body the sand computed in no substep slept in it, with the sand around it: the force
      // on it is the last one computed.
      const Vec3 force = f.substeps > 0 ? f.meanForce() : m_lastForce[i];
      const Vec3 torque = f.substeps > 0 ? f.meanTorque() : m_lastTorque[i];
      c.body->applyCentralForce(toBullet(force));
      c.body->applyTorque(toBullet(torque));
      if (f.substeps > 0) {
        m_lastForce[i] = force;
        m_lastTorque[i] = torque;
        // Sand that pushes a body Bullet put to sleep harder (or less) than it did then wakes it.
        const float mass = float(btScalar(1) / c.body->getInvMass());
        const float limit = m_wakeAcceleration * mass;
        if (c.asleep && ((toBullet(force) - toBullet(c.restForce)).length() > limit ||
                         (toBullet(torque) - toBullet(c.restTorque)).length() > limit * c.reach)) {
          c.body->activate();
        }
      }
      m_frameForce[i] += float(weight) * force;
      m_frameTorque[i] += float(weight) * torque;
      break;
    }
  }
}

StepReport Bridge::step(float frameDt) {
  StepReport report;
  if (!std::isfinite(frameDt) || frameDt <= 0.0f) return report;
  const auto exchanges = std::max(1, int(std::ceil(double(frameDt) / automaticStep() - 1e-6)));
  const float h = frameDt / float(exchanges);
  m_lastStep = h;
  m_lastExchanges = exchanges;
  m_pushes.clear();
  std::fill(m_frameForce.begin(), m_frameForce.end(), Vec3{});
  std::fill(m_frameTorque.begin(), m_frameTorque.end(), Vec3{});
  for (int i = 0; i < exchanges; ++i) {
    pushPoses();
    const StepReport exchange = m_sand.step(h);
    // The frame's report: totals over the exchanges, the statistics of the last.
    report.substeps += exchange.substeps;
    report.idleSubsteps += exchange.idleSubsteps;
    report.simulatedTime += exchange.simulatedTime;
    report.droppedTime += exchange.droppedTime;
    report.granulesEmitted += exchange.granulesEmitted;
    report.emitterBlocked = report.emitterBlocked || exchange.emitterBlocked;
    report.hasStats = exchange.hasStats;
    report.stats = exchange.stats;
    applySandForces(1.0 / exchanges);
    // One fixed step of exactly h: the forces just applied act over the same span the sand
    // measured them on.
    m_dynamics.stepSimulation(h, 0);
  }
  for (std::size_t i = 0; i < m_coupled.size(); ++i) {
    m_coupled[i].force = m_frameForce[i];
    m_coupled[i].torque = m_frameTorque[i];
  }
  return report;
}

}  // namespace sandphys::bullet
