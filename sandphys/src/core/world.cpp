#include "sandphys/world.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <variant>

#include "core/collider_bounds.h"
#include "core/contact_state.h"
#include "core/granule_spawner.h"
#include "core/overlap_check.h"
#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"
#include "gl/gl_check.h"

namespace sandphys {

using namespace detail;

namespace {

// Collider keys of contact slots hold collider * 8 + face in 23 bits (contact_slots.glsl); the
// contact kernel loops over every collider, so far fewer are practical.
constexpr std::uint32_t kMaxColliders = 1u << 16;
// A granule whose centre is this many diameters from a collider's surface may touch it: a
// particle's radius plus the granule's bounding radius, with room to spare.
constexpr float kColliderWakeMargin = 2.0f;

GpuVec4 toGpu(Vec3 v, float w) {
  return {v.x, v.y, v.z, w};
}

// Quaternion product a · b, both (w, x, y, z).
Quat multiply(Quat a, Quat b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

void requireSurface(const std::string& type, const SurfaceMaterial& m) {
  requireNonNegative(type + ".material.friction", m.friction, "");
  require(std::isfinite(m.restitution) && m.restitution > 0.0f && m.restitution <= 1.0f,
          type + ".material.restitution", m.restitution, "must be in (0, 1]");
}

GpuVec4 surfaceParams(ColliderType type, const SurfaceMaterial& m) {
  return {float(type), m.friction, float(hertzDampingFactor(m.restitution)), 0.0f};
}

// The surface velocity v + ω × (x - reference) as the kernel evaluates it: v0 + ω × x with
// v0 = v - ω × reference.
void setMotion(GpuCollider& c, const std::string& type, const ColliderMotion& m, Vec3 reference) {
  requireFiniteVec(type + ".motion.velocity", m.velocity);
  requireFiniteVec(type + ".motion.angularVelocity", m.angularVelocity);
  const Vec3 w = m.angularVelocity;
  const Vec3 wxr{w.y * reference.z - w.z * reference.y, w.z * reference.x - w.x * reference.z,
                 w.x * reference.y - w.y * reference.x};
  c.velocity = {m.velocity.x - wxr.x, m.velocity.y - wxr.y, m.velocity.z - wxr.z, 0.0f};
  c.spin = toGpu(w, 0.0f);
}

GpuCollider toGpu(const Plane& p) {
  requireFiniteVec("Plane.normal", p.normal);
  requireFinite("Plane.offset", p.offset);
  requireSurface("Plane", p.material);
  double n = std::sqrt(double(p.normal.x) * p.normal.x + double(p.normal.y) * p.normal.y +
                       double(p.normal.z) * p.normal.z);
  require(n > 1e-12, "Plane.normal (length)", n, "must be non-zero");
  // dot(n/|n|, x) < offset/|n| describes the same half-space.
  GpuCollider c{
      {float(p.normal.x / n), float(p.normal.y / n), float(p.normal.z / n), float(p.offset / n)},
      {},
      {},
      surfaceParams(kColliderPlane, p.material)};
  const float o = c.a.w;
  setMotion(c, "Plane", p.motion, {c.a.x * o, c.a.y * o, c.a.z * o});
  return c;
}

GpuCollider toGpu(const Box& b) {
  requireFiniteVec("Box.center", b.center);
  requirePositive("Box.halfExtents.x", b.halfExtents.x, "(m)");
  requirePositive("Box.halfExtents.y", b.halfExtents.y, "(m)");
  requirePositive("Box.halfExtents.z", b.halfExtents.z, "(m)");
  requireSurface("Box", b.material);
  Quat q = normalised(b.orientation, "Box.orientation");
  GpuCollider c{toGpu(b.center, b.inside ? 1.0f : 0.0f),
                toGpu(b.halfExtents, 0.0f),
                {q.x, q.y, q.z, q.w},
                surfaceParams(kColliderBox, b.material)};
  setMotion(c, "Box", b.motion, b.center);
  return c;
}

GpuCollider toGpu(const Cylinder& c) {
  requireFiniteVec("Cylinder.base", c.base);
  requirePositive("Cylinder.radius", c.radius, "(m)");
  requirePositive("Cylinder.height", c.height, "(m)");
  requireSurface("Cylinder", c.material);
  GpuCollider g{toGpu(c.base, 0.0f),
                {c.radius, 0.0f, c.radius, c.height},
                {},
                surfaceParams(kColliderRevolution, c.material)};
  setMotion(g, "Cylinder", c.motion, c.base);
  return g;
}

GpuCollider toGpu(const Funnel& f) {
  requireFiniteVec("Funnel.outletCenter", f.outletCenter);
  requireNonNegative("Funnel.outletRadius", f.outletRadius, "(m)");
  require(std::isfinite(f.halfAngle) && f.halfAngle > 0.0f &&
              f.halfAngle < 0.5f * std::numbers::pi_v<float>,
          "Funnel.halfAngle", f.halfAngle, "must be in (0, pi/2) rad");
  requirePositive("Funnel.height", f.height, "(m)");
  requireSurface("Funnel", f.material);
  float top = f.outletRadius + f.height * std::tan(f.halfAngle);
  GpuCollider c{toGpu(f.outletCenter, 0.0f),
                {f.outletRadius, 0.0f, top, f.height},
                {},
                surfaceParams(kColliderRevolution, f.material)};
  setMotion(c, "Funnel", f.motion, f.outletCenter);
  return c;
}

}  // namespace

World::Impl::Impl(const GpuContext& context, const WorldSettings& s) : gpu(&context), settings(s) {
  World::checkSettings(settings);
  model = ContactModel::fromSettings(settings);
  sleep = SleepModel::fromSettings(settings, model.timeStep);
  bodyCapacity = settings.maxBodies;
  particleCapacity = settings.maxParticles ? settings.maxParticles : 4u * settings.maxBodies;
  tableCapacity = HashTable::sizeFor(particleCapacity);
  table = HashTable::forParticles(0);
  granule = tetrahedronTemplate(settings.particleDiameter, settings.material.density);

  context.makeCurrent();
  kernels.compile(settings.contactLaw, sleep.enabled);
  buffers.allocate(bodyCapacity, particleCapacity, tableCapacity, settings.maxColliders, 0, 0,
                   keepsHistory());
  profiler.setEnabled(settings.profileKernels);
  uploadParams();
}

World::Impl::~Impl() {
  gpu->makeCurrent();
  kernels.release();
}

std::uint32_t World::Impl::addBodies(const ParticleTemplate& shape,
                                     const std::vector<BodyDesc>& descs, bool isGranule) {
  const std::uint64_t n = descs.size();
  const std::uint64_t perBody = shape.offsets.size();
  requireRoom(n, n * perBody);
  // Every body that is not a granule (and not static) gets a workgroup and a force sum of its
  // own (integrate_large_bodies.comp), from a fixed-size list.
  auto isLarge = [&](const BodyDesc& d) { return !isGranule && d.motion != Motion::Static; };
  const auto large = std::uint64_t(std::count_if(descs.begin(), descs.end(), isLarge));
  if (largeBodies.size() + large > kMaxLargeBodies) {
    throw CapacityExceeded("adding " + std::to_string(large) + " bodies that are not granules to " +
                           std::to_string(largeBodies.size()) + " exceeds the limit of " +
                           std::to_string(kMaxLargeBodies) + " such bodies per World");
  }
  gpu->makeCurrent();
  const std::uint32_t firstBody = bodyCount;
  const std::uint32_t firstParticle = particleCount;

  std::vector<GpuUVec4> info(n);
  std::vector<GpuVec4> inertia(n);
  std::vector<GpuVec4> local(n * perBody);
  std::vector<std::uint32_t> owner(n * perBody);
  for (std::uint64_t i = 0; i < n; ++i) {
    const Motion motion = descs[i].motion;
    const bool dynamic = motion == Motion::Dynamic;
    const std::uint32_t flags = kBodyAlive | (isGranule ? kBodyGranule : 0u) |
                                (isLarge(descs[i]) ? kBodyLarge : 0u) |
                                (std::uint32_t(motion) << kBodyMotionShift);
    info[i] = {std::uint32_t(firstParticle + i * perBody), std::uint32_t(perBody), flags, 0u};
    inertia[i] = toGpu(shape.principalInertia, shape.mass);
    // -1 marks static particles, whose force the contact kernel skips (layout.glsl). The paper's
    // law damps with the particle's share of the mass, HertzMindlin with the body's.
    const float inverseMass = keepsHistory() ? 1.0f / shape.mass : float(perBody) / shape.mass;
    const float particleInvMass = dynamic ? inverseMass : (motion == Motion::Static ? -1.0f : 0.0f);
    for (std::uint64_t k = 0; k < perBody; ++k) {
      local[i * perBody + k] = toGpu(shape.offsets[k], particleInvMass);
      owner[i * perBody + k] = std::uint32_t(firstBody + i);
    }
  }
  buffers[kBodyInfo].upload(firstBody * 16ull, n * 16, info.data());
  buffers[kBodyInertia].upload(firstBody * 16ull, n * 16, inertia.data());
  buffers[kParticleLocal].upload(firstParticle * 16ull, local.size() * 16, local.data());
  buffers[kParticleBody].upload(firstParticle * 4ull, owner.size() * 4, owner.data());
  for (std::uint64_t i = 0; i < n; ++i) {
    if (!isLarge(descs[i])) continue;
    const auto entry = std::uint32_t(largeBodies.size());
    const auto slot = std::uint32_t(firstBody + i);
    const GpuVec4 zeros[2] = {};
    buffers[kLargeBodies].upload(entry * 4ull, 4, &slot);
    buffers[kLargeBodyForces].upload(entry * 32ull, 32, zeros);
    largeBodies.push_back(slot);
  }
  bodyCount += std::uint32_t(n);
  particleCount += std::uint32_t(n * perBody);
  generations.resize(bodyCount, 0);
  principalRotations.resize(bodyCount, shape.principalRotation);
  for (const BodyDesc& d : descs) bodyMotions.push_back(d.motion);
  bodyMasses.resize(bodyCount, shape.mass);
  for (std::uint64_t i = 0; i < n; ++i)
    particleEnds.push_back(std::uint32_t(firstParticle + (i + 1) * perBody));
  boundingRadii.resize(bodyCount, shape.boundingRadius);
  uploadBodyStates(firstBody, descs, shape);
  // New particles: their state before the next contacts, and lists that hold them.
  markParticlesDirty(firstParticle, particleCount);
  listsStale = true;
  if (isGranule) granulesSpawned += std::uint32_t(n);
  paramsDirty = true;
  return firstBody;
}

void World::Impl::requireRoom(std::uint64_t bodies, std::uint64_t particles) const {
  if (bodyCount + bodies > bodyCapacity) {
    throw CapacityExceeded("adding " + std::to_string(bodies) + " bodies to " +
                           std::to_string(bodyCount) + " exceeds WorldSettings.maxBodies = " +
                           std::to_string(bodyCapacity) + " (grow it with World::reserve)");
  }
  if (particleCount + particles > particleCapacity) {
    throw CapacityExceeded(
        "adding " + std::to_string(particles) + " particles to " + std::to_string(particleCount) +
        " exceeds WorldSettings.maxParticles = " + std::to_string(particleCapacity) +
        " (grow it with World::reserve)");
  }
}

void World::Impl::checkOverlapsFrom(std::uint32_t firstBody) {
  const std::uint32_t first = firstBody == 0 ? 0u : particleEnd(firstBody - 1);
  if (overlapCheckEnd <= overlapCheckBegin) overlapCheckBegin = first;
  overlapCheckBegin = std::min(overlapCheckBegin, first);
  overlapCheckEnd = particleCount;
}

std::uint32_t World::Impl::placedCalm(const BodyDesc& d) const {
  // A dynamic body placed at rest may be about to fall: it starts moving.
  if (!sleep.enabled || d.motion != Motion::Kinematic) return 0;
  // A kinematic body slower than the thresholds is calm, one short of sleep, so that a body an
  // engine sets at rest every frame (a Bullet body) does not wake the sand under it.
  const auto below = [](Vec3 v, float limit) {
    return double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z < double(limit) * limit;
  };
  const bool calm =
      below(d.velocity, sleep.linearSpeed) && below(d.angularVelocity, sleep.angularSpeed);
  return calm ? sleep.substeps - 1 : 0;
}

void World::Impl::uploadBodyStates(std::uint32_t first, const std::vector<BodyDesc>& descs,
                                   const ParticleTemplate& shape) {
  const std::size_t n = descs.size();
  std::vector<GpuVec4> position(n), orientation(n), velocity(n), spin(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyDesc& d = descs[i];
    const bool dynamic = d.motion == Motion::Dynamic;
    Quat q = multiply(d.orientation, principalRotations[first + i]);
    position[i] = toGpu(d.position, dynamic ? 1.0f / shape.mass : 0.0f);
    orientation[i] = {q.x, q.y, q.z, q.w};
    velocity[i] = toGpu(d.motion == Motion::Static ? Vec3{} : d.velocity,
                        std::bit_cast<float>(placedCalm(d)));
    spin[i] = toGpu(d.motion == Motion::Static ? Vec3{} : d.angularVelocity, shape.boundingRadius);
  }
  buffers[kBodyPosition].upload(first * 16ull, n * 16, position.data());
  buffers[kBodyOrientation].upload(first * 16ull, n * 16, orientation.data());
  buffers[kBodyVelocity].upload(first * 16ull, n * 16, velocity.data());
  buffers[kBodyAngularVelocity].upload(first * 16ull, n * 16, spin.data());
}

void World::Impl::requireImpenetrableSurface(const ParticleTemplate& shape) const {
  if (!keepsHistory() || shape.surfaceSpacing <= 0.0f) return;
  // A granule meeting the sampled surface at maxSpeed, as a RoughFloor is checked.
  const double d = settings.particleDiameter;
  requireNoPassThrough(settings, model.peakOverlapFixedParticle,
                       surfacePassOverlap(shape.surfaceSpacing / d),
                       "a granule meeting a surface sampled at a spacing of " +
                           formatValue(shape.surfaceSpacing / d) + " d at maxSpeed");
}

void World::Impl::requireUntunnelledWall(const ColliderShape& shape) const {
  const ColliderMotion* motion = nullptr;
  double reach = 0.0;  // farthest point of the wall from the point its motion refers to, m
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    motion = &c->motion;
    reach = std::hypot(double(c->radius), double(c->height));
  } else if (const auto* f = std::get_if<Funnel>(&shape)) {
    motion = &f->motion;
    reach = std::hypot(f->outletRadius + f->height * std::tan(double(f->halfAngle)), f->height);
  }
  if (!motion || !keepsHistory()) return;
  const auto length = [](Vec3 v) { return std::hypot(double(v.x), double(v.y), double(v.z)); };
  const double wallSpeed = length(motion->velocity) + length(motion->angularVelocity) * reach;
  if (wallSpeed == 0.0) return;  // ContactModel::fromSettings checked the wall at rest
  // A particle meets a moving thin wall at up to its own fastest speed plus the wall's.
  const double speed = kGuardParticleSpeed * settings.maxSpeed + wallSpeed;
  const double peak = hertzPeakOverlap(model.granuleMass, model.stiffnessWall, speed);
  const double d = settings.particleDiameter;
  require(peak <= kThinWallPassOverlap * d, "ColliderMotion (surface speed, m/s)", wallSpeed,
          "a thin wall (cylinder, funnel) moving this fast meets a granule's particle at up to " +
              formatValue(speed) + " m/s, where it would overlap by " + formatValue(peak / d) +
              " d (closed-form Hertz peak), past " + formatValue(kThinWallPassOverlap) +
              " d where the particle passes through; move it slower, or raise "
              "WorldSettings.material.youngsModulus");
}

ColliderId World::Impl::putCollider(std::optional<std::uint32_t> slot, const GpuCollider& collider,
                                    const ColliderShape& shape) {
  requireUntunnelledWall(shape);
  gpu->makeCurrent();
  std::uint32_t index = slot ? *slot : std::uint32_t(colliders.size());
  if (!slot) {
    if (colliders.size() >= settings.maxColliders) {
      throw CapacityExceeded("adding a collider exceeds WorldSettings.maxColliders = " +
                             std::to_string(settings.maxColliders));
    }
    colliders.push_back(collider);
    colliderShapes.push_back(shape);
  } else {
    if (index >= colliders.size())
      throw InvalidId("ColliderId " + std::to_string(index) + " does not exist");
    GpuCollider changed = collider;
    std::memcpy(&changed.material.w, &index, sizeof index);
    if (std::memcmp(&changed, &colliders[index], sizeof changed) == 0) return ColliderId{index};
    // A sleeping granule touches no collider it does not see: the sand where the collider was
    // wakes (where it is now wakes below).
    wakeBox(colliderBounds(colliderShapes[index], kColliderWakeMargin * settings.particleDiameter));
    colliders[index] = collider;
    colliderShapes[index] = shape;
  }
  std::memcpy(&colliders[index].material.w, &index, sizeof index);
  paramsDirty = true;  // uploadParams re-sorts and uploads the colliders
  wakeBox(colliderBounds(shape, kColliderWakeMargin * settings.particleDiameter));
  return ColliderId{index};
}

void World::Impl::wakeBox(const Bounds& box) {
  if (!sleep.enabled || bodyCount == 0) return;
  gpu->makeCurrent();
  if (paramsDirty) uploadParams();
  buffers.bindAll();
  glUseProgram(kernels.wakeRegion);
  glUniform3f(0, box.lo.x, box.lo.y, box.lo.z);
  glUniform3f(1, box.hi.x, box.hi.y, box.hi.z);
  dispatch(kernels.wakeRegion, "wake_region", bodyCount, kWorkgroupSize);
  gl::check("waking a region");
}

void World::Impl::requireBody(BodyId id) const {
  if (!id.isValid() || id.index >= bodyCount || generations[id.index] != id.generation) {
    throw InvalidId("BodyId {index " + std::to_string(id.index) + ", generation " +
                    std::to_string(id.generation) +
                    "} is invalid or stale (bodies: " + std::to_string(bodyCount) + ")");
  }
}

// --- World ------------------------------------------------------------------------------------

void World::checkSettings(const WorldSettings& settings) {
  const ContactModel model = ContactModel::fromSettings(settings);
  (void)SleepModel::fromSettings(settings, model.timeStep);
  require(settings.maxSubstepsPerFrame > 0, "WorldSettings.maxSubstepsPerFrame",
          settings.maxSubstepsPerFrame, "must be > 0");
  require(settings.maxBodies > 0, "WorldSettings.maxBodies", settings.maxBodies, "must be > 0");
  require(settings.maxColliders > 0 && settings.maxColliders <= kMaxColliders,
          "WorldSettings.maxColliders", settings.maxColliders,
          "must be in [1, " + std::to_string(kMaxColliders) + "]");
  const std::uint64_t particles =
      settings.maxParticles ? settings.maxParticles : 4ull * settings.maxBodies;
  require(particles <= kMaxParticleCapacity, "WorldSettings.maxParticles", double(particles),
          "must be <= " + std::to_string(kMaxParticleCapacity) + " (GPU buffer limit)");
}

World::World(const GpuContext& gpu, const WorldSettings& settings)
    : m_impl(std::make_unique<Impl>(gpu, settings)) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const WorldSettings& World::settings() const {
  return impl().settings;
}
const ContactModel& World::contactModel() const {
  return impl().model;
}
const SleepModel& World::sleepModel() const {
  return impl().sleep;
}
float World::timeStep() const {
  return impl().model.timeStep;
}
World::Impl& World::impl() {
  if (!m_impl)
    throw InvalidArgument("World: used after it was moved from (move-assign a World to it first)");
  return *m_impl;
}
const World::Impl& World::impl() const {
  if (!m_impl)
    throw InvalidArgument("World: used after it was moved from (move-assign a World to it first)");
  return *m_impl;
}

ColliderId World::addCollider(const Plane& plane) {
  return impl().putCollider({}, toGpu(plane), plane);
}
ColliderId World::addCollider(const Box& box) {
  return impl().putCollider({}, toGpu(box), box);
}
ColliderId World::addCollider(const Cylinder& c) {
  return impl().putCollider({}, toGpu(c), c);
}
ColliderId World::addCollider(const Funnel& f) {
  return impl().putCollider({}, toGpu(f), f);
}
void World::setCollider(ColliderId id, const Plane& p) {
  impl().putCollider(id.index, toGpu(p), p);
}
void World::setCollider(ColliderId id, const Box& b) {
  impl().putCollider(id.index, toGpu(b), b);
}
void World::setCollider(ColliderId id, const Cylinder& c) {
  impl().putCollider(id.index, toGpu(c), c);
}
void World::setCollider(ColliderId id, const Funnel& f) {
  impl().putCollider(id.index, toGpu(f), f);
}

namespace {

Vec3 displacementRate(Vec3 from, Vec3 to, float seconds) {
  return {(to.x - from.x) / seconds, (to.y - from.y) / seconds, (to.z - from.z) / seconds};
}

// The plane's point nearest the origin (its motion's reference point).
Vec3 planePoint(const Plane& p) {
  const double n2 = double(p.normal.x) * p.normal.x + double(p.normal.y) * p.normal.y +
                    double(p.normal.z) * p.normal.z;
  const double k = n2 > 0.0 ? p.offset / n2 : 0.0;
  return {float(p.normal.x * k), float(p.normal.y * k), float(p.normal.z * k)};
}

// The angular velocity that turns `from` into `to` in `seconds` (shortest way).
Vec3 rotationRate(Quat from, Quat to, float seconds) {
  from = normalised(from, "Box.orientation");
  to = normalised(to, "Box.orientation");
  Quat d = multiply(to, {from.w, -from.x, -from.y, -from.z});
  if (d.w < 0.0f) d = {-d.w, -d.x, -d.y, -d.z};
  const double s = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
  if (s == 0.0) return {};
  const double rate = 2.0 * std::atan2(s, double(d.w)) / s / seconds;
  return {float(d.x * rate), float(d.y * rate), float(d.z * rate)};
}

// `shape` with the motion that takes the collider from `before` to it in `seconds`.
ColliderShape withDerivedMotion(const ColliderShape& before, ColliderShape shape, float seconds) {
  if (before.index() != shape.index()) {
    std::visit([](auto& s) { s.motion = {}; }, shape);
    return shape;
  }
  if (auto* p = std::get_if<Plane>(&shape)) {
    p->motion = {displacementRate(planePoint(std::get<Plane>(before)), planePoint(*p), seconds),
                 {}};
  } else if (auto* b = std::get_if<Box>(&shape)) {
    const Box& old = std::get<Box>(before);
    b->motion = {displacementRate(old.center, b->center, seconds),
                 rotationRate(old.orientation, b->orientation, seconds)};
  } else if (auto* c = std::get_if<Cylinder>(&shape)) {
    c->motion = {displacementRate(std::get<Cylinder>(before).base, c->base, seconds), {}};
  } else if (auto* f = std::get_if<Funnel>(&shape)) {
    f->motion = {displacementRate(std::get<Funnel>(before).outletCenter, f->outletCenter, seconds),
                 {}};
  }
  return shape;
}

}  // namespace

void World::moveCollider(ColliderId id, const ColliderShape& shape, float seconds) {
  requirePositive("World::moveCollider seconds", seconds, "(s)");
  if (!id.isValid() || id.index >= impl().colliderShapes.size()) {
    throw InvalidId("ColliderId " + std::to_string(id.index) + " does not exist");
  }
  const ColliderShape moved = withDerivedMotion(impl().colliderShapes[id.index], shape, seconds);
  std::visit([&](const auto& s) { setCollider(id, s); }, moved);
}

SinkId World::addSink(const Sink& sink) {
  requireFiniteVec("Sink.min", sink.min);
  requireFiniteVec("Sink.max", sink.max);
  require(sink.min.x <= sink.max.x && sink.min.y <= sink.max.y && sink.min.z <= sink.max.z,
          "Sink.max.x/y/z", sink.max.x, "must be >= Sink.min on every axis");
  Impl& w = impl();
  if (w.sinks.size() >= w.settings.maxColliders) {
    throw CapacityExceeded("adding a sink exceeds WorldSettings.maxColliders = " +
                           std::to_string(w.settings.maxColliders));
  }
  w.gpu->makeCurrent();
  GpuSink gpuSink{toGpu(sink.min, 0.0f), toGpu(sink.max, 0.0f)};
  w.buffers[kSinks].upload(w.sinks.size() * sizeof(GpuSink), sizeof(GpuSink), &gpuSink);
  w.sinks.push_back(gpuSink);
  w.paramsDirty = true;
  // A sleeping granule is not integrated, so a sink would not take it.
  wake(sink.min, sink.max);
  return SinkId{std::uint32_t(w.sinks.size() - 1)};
}

void World::wake(Vec3 lo, Vec3 hi) {
  requireFiniteVec("World::wake lo", lo);
  requireFiniteVec("World::wake hi", hi);
  require(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z, "World::wake hi.x/y/z", hi.x,
          "must be >= lo on every axis");
  impl().wakeBox({lo, hi});
}

BodyId World::addRoughFloor(const RoughFloor& floor) {
  requireFiniteVec("RoughFloor.center", floor.center);
  requireNonNegative("RoughFloor.radius", floor.radius, "(m)");
  requireNonNegative("RoughFloor.spacing", floor.spacing, "(m)");
  const float d = impl().settings.particleDiameter;
  const double spacing = floor.spacing > 0.0f ? floor.spacing : d;
  double hx = floor.radius, hz = floor.radius;
  if (floor.radius == 0.0f) {
    requirePositive("RoughFloor.halfExtentX", floor.halfExtentX, "(m) (or give a radius)");
    requirePositive("RoughFloor.halfExtentZ", floor.halfExtentZ, "(m) (or give a radius)");
    hx = floor.halfExtentX;
    hz = floor.halfExtentZ;
  }
  if (impl().keepsHistory()) {
    // A granule landing on the floor at maxSpeed must not slip between its particles.
    requireNoPassThrough(
        impl().settings, impl().model.peakOverlapFixedParticle, floorPassOverlap(spacing / d),
        "a granule meeting a RoughFloor of spacing " + formatValue(spacing / d) + " d at maxSpeed");
  }
  requireResolvable("RoughFloor.center", floor.center, std::sqrt(hx * hx + hz * hz), d);
  // Counted before anything is built: a floor too large for the World costs no memory.
  Impl& w = impl();
  const std::uint64_t room = std::uint64_t(w.particleCapacity) - w.particleCount;
  const double radius = floor.radius;
  w.requireRoom(1, roughFloorParticles(spacing, hx, hz, radius, room));
  const auto nx = std::int64_t(std::floor(hx / spacing));
  const auto nz = std::int64_t(std::floor(hz / spacing));
  std::vector<Vec3> centres;
  for (std::int64_t z = -nz; z <= nz; ++z) {
    for (std::int64_t x = -nx; x <= nx; ++x) {
      double px = double(x) * spacing, pz = double(z) * spacing;
      if (radius > 0.0 && !inRoughFloor(px, pz, radius)) continue;
      centres.push_back({float(px), 0.0f, float(pz)});
    }
  }
  // A static body: its mass does not matter; keep the template frame (no principal rotation).
  ParticleTemplate shape;
  shape.offsets = centres;
  shape.mass = 1.0f;
  shape.principalInertia = {1.0f, 1.0f, 1.0f};
  shape.boundingRadius = float(std::sqrt(hx * hx + hz * hz));
  std::uint32_t index =
      w.addBodies(shape, {BodyDesc{floor.center, {}, {}, {}, Motion::Static}}, false);
  w.checkOverlapsFrom(index);
  return BodyId{index, w.generations[index]};
}

BodyId World::addBody(const ParticleTemplate& shape, const BodyDesc& desc) {
  requireTemplate(shape);
  impl().requireImpenetrableSurface(shape);
  requireFiniteVec("BodyDesc.position", desc.position);
  requireResolvable("BodyDesc.position", desc.position, shape.boundingRadius,
                    impl().settings.particleDiameter);
  requireFiniteVec("BodyDesc.velocity", desc.velocity);
  requireFiniteVec("BodyDesc.angularVelocity", desc.angularVelocity);
  BodyDesc d = desc;
  d.orientation = normalised(desc.orientation, "BodyDesc.orientation");
  std::uint32_t index = impl().addBodies(shape, {d}, false);
  impl().checkOverlapsFrom(index);
  return BodyId{index, impl().generations[index]};
}

BodyRange World::addGranules(const GranuleBlock& block) {
  Impl& w = impl();
  const float d = w.settings.particleDiameter;
  const double spacing = granuleBlockSpacing(block, d);
  // Counted and placed before anything is built: a block too large for the World costs no
  // memory.
  const auto count =
      std::uint64_t(std::min(double(block.countX) * block.countY * block.countZ, 0x1.0p60));
  w.requireRoom(count, count * w.granule.offsets.size());
  const auto halfExtent = [&](std::uint32_t n) {
    return (0.5 * (n - 1.0) + double(block.jitter)) * spacing;
  };
  requireResolvable(
      "GranuleBlock.center", block.center,
      std::hypot(halfExtent(block.countX), halfExtent(block.countY), halfExtent(block.countZ)) +
          w.granule.boundingRadius,
      d);
  auto spawns = layoutGranuleBlock(block, d);
  std::vector<BodyDesc> descs;
  descs.reserve(spawns.size());
  for (const auto& s : spawns)
    descs.push_back({s.position, s.orientation, s.velocity, {}, Motion::Dynamic});
  std::uint32_t first = w.addBodies(w.granule, descs, true);
  w.checkOverlapsFrom(first);
  return {first, std::uint32_t(descs.size())};
}

EmitterId World::addEmitter(const EmitterSettings& emitter) {
  Impl& w = impl();
  w.emitters.emplace_back(EmitterState(emitter, w.settings.particleDiameter, w.bodyCapacity));
  return EmitterId{std::uint32_t(impl().emitters.size() - 1)};
}

void World::removeEmitter(EmitterId id) {
  if (!id.isValid() || id.index >= impl().emitters.size() || !impl().emitters[id.index]) {
    throw InvalidId("EmitterId " + std::to_string(id.index) + " does not exist");
  }
  impl().emitters[id.index].reset();
}

void World::setBodyState(BodyId id, const BodyDesc& state) {
  impl().requireBody(id);
  requireFiniteVec("BodyDesc.position", state.position);
  requireFiniteVec("BodyDesc.velocity", state.velocity);
  requireFiniteVec("BodyDesc.angularVelocity", state.angularVelocity);
  Impl& w = impl();
  requireResolvable("BodyDesc.position", state.position, w.boundingRadii[id.index],
                    w.settings.particleDiameter);
  BodyDesc d = state;
  d.orientation = normalised(state.orientation, "BodyDesc.orientation");
  const Motion added = w.bodyMotions[id.index];
  if (state.motion != added) {
    throw InvalidArgument("BodyDesc.motion = " + std::to_string(unsigned(state.motion)) +
                          " for body " + std::to_string(id.index) +
                          ": a body keeps the motion it was added with (" +
                          std::to_string(unsigned(added)) + "; 0 dynamic, 1 kinematic, 2 static)");
  }
  w.gpu->makeCurrent();
  // The body's mass data stay as they were (kept on the CPU: no sync, so a bridge can call this
  // every frame).
  ParticleTemplate massOnly;
  massOnly.mass = w.bodyMasses[id.index];
  massOnly.boundingRadius = w.boundingRadii[id.index];
  w.uploadBodyStates(id.index, {d}, massOnly);
  // Its particles follow before the next contacts (and ask for a list build if they jumped).
  const std::uint32_t first = id.index == 0 ? 0u : w.particleEnd(id.index - 1);
  w.markParticlesDirty(first, w.particleEnd(id.index));
}

void World::restoreSnapshot(const WorldSnapshot& snapshot) {
  Impl& w = impl();
  const auto slots = static_cast<std::uint32_t>(snapshot.bodies.size());
  require(slots <= w.bodyCount, "WorldSnapshot.bodies.size()", slots,
          "must be <= the World's " + std::to_string(w.bodyCount) +
              " body slots (restore a snapshot into the World that reached its frame, or later)");
  requireRestorable(snapshot);
  // The snapshot's bodies own the first particles; their contact history must come with them.
  const std::uint32_t particles = slots == 0 ? 0u : w.particleEnd(slots - 1);
  const std::size_t expected = w.keepsHistory() ? particles : 0u;
  require(snapshot.contacts.size() == expected, "WorldSnapshot.contacts.size()",
          double(snapshot.contacts.size()),
          "must be " + std::to_string(expected) +
              (w.keepsHistory() ? " (the particles of its bodies, under ContactLaw::HertzMindlin)"
                                : " (ContactLaw::PaperViscous keeps no contact history)"));
  w.gpu->makeCurrent();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  // Only the snapshot's fields change: each vec4's w (mass, inverse mass and the like) and the
  // other flags stay as the World has them.
  const std::size_t count = w.bodyCount;
  std::vector<GpuVec4> position(count), orientation(count), velocity(count), spin(count);
  std::vector<GpuUVec4> info(count);
  w.buffers[kBodyPosition].download(0, count * sizeof(GpuVec4), position.data());
  w.buffers[kBodyOrientation].download(0, count * sizeof(GpuVec4), orientation.data());
  w.buffers[kBodyVelocity].download(0, count * sizeof(GpuVec4), velocity.data());
  w.buffers[kBodyAngularVelocity].download(0, count * sizeof(GpuVec4), spin.data());
  w.buffers[kBodyInfo].download(0, count * sizeof(GpuUVec4), info.data());
  for (std::size_t i = 0; i < count; ++i) {
    if (i >= slots) {
      info[i].z &= ~kBodyAlive;
      continue;
    }
    const StoredBody& b = snapshot.bodies[i];
    position[i] = {b.position[0], b.position[1], b.position[2], position[i].w};
    orientation[i] = {b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]};
    velocity[i] = {b.velocity[0], b.velocity[1], b.velocity[2], std::bit_cast<float>(b.calm)};
    spin[i] = {b.angularVelocity[0], b.angularVelocity[1], b.angularVelocity[2], spin[i].w};
    info[i].z = b.alive ? (info[i].z | kBodyAlive) : (info[i].z & ~kBodyAlive);
  }
  w.buffers[kBodyPosition].upload(0, count * sizeof(GpuVec4), position.data());
  w.buffers[kBodyOrientation].upload(0, count * sizeof(GpuVec4), orientation.data());
  w.buffers[kBodyVelocity].upload(0, count * sizeof(GpuVec4), velocity.data());
  w.buffers[kBodyAngularVelocity].upload(0, count * sizeof(GpuVec4), spin.data());
  w.buffers[kBodyInfo].upload(0, count * sizeof(GpuUVec4), info.data());
  if (w.keepsHistory()) uploadContacts(w.buffers, snapshot.contacts, w.particleCount);
  gl::check("World::restoreSnapshot");
  w.steps = snapshot.steps;
  w.simTime = snapshot.simulatedTime;
  w.gridValid = false;
  w.markParticlesDirty(0, w.particleCount);
  w.listsStale = true;
  w.accumulator = snapshot.unsteppedTime;
}

void World::reserve(std::uint32_t maxBodies, std::uint32_t maxParticles) {
  Impl& w = impl();
  require(maxParticles <= kMaxParticleCapacity, "World::reserve maxParticles", maxParticles,
          "must be <= " + std::to_string(kMaxParticleCapacity) + " (GPU buffer limit)");
  w.gpu->makeCurrent();
  w.bodyCapacity = std::max(w.bodyCapacity, maxBodies);
  w.particleCapacity = std::max(w.particleCapacity, maxParticles);
  w.tableCapacity = HashTable::sizeFor(w.particleCapacity);
  w.buffers.allocate(w.bodyCapacity, w.particleCapacity, w.tableCapacity, w.settings.maxColliders,
                     w.bodyCount, w.particleCount, w.keepsHistory());
  w.paramsDirty = true;
  // A grown table, and grown lists, are new, empty buffers.
  w.gridValid = false;
  w.listsStale = true;
}

StepReport World::step(float frameDt) {
  Impl& w = impl();
  StepReport report;
  if (!std::isfinite(frameDt) || frameDt <= 0.0f) return report;
  w.gpu->makeCurrent();
  w.accumulator += frameDt;
  const double dt = w.model.timeStep;
  // Compared in double before any integer conversion: a frame of more substeps than an integer
  // holds is dropped like any other beyond the cap, never wrapped to none.
  const double needed = std::floor(w.accumulator / dt);
  std::uint64_t due = 0;
  if (needed > double(w.settings.maxSubstepsPerFrame)) {
    report.droppedTime = float((needed - w.settings.maxSubstepsPerFrame) * dt);
    if (!w.warnedDroppedTime) {
      std::fprintf(stderr,
                   "sandphys: a frame of %.4g s needs %.4g substeps of %.3g s, more than "
                   "WorldSettings.maxSubstepsPerFrame = %u; the rest is dropped (slow motion). "
                   "This warning is printed once; StepReport::droppedTime has every frame's.\n",
                   double(frameDt), needed, dt, w.settings.maxSubstepsPerFrame);
      w.warnedDroppedTime = true;
    }
    due = w.settings.maxSubstepsPerFrame;
    w.accumulator = 0.0;
  } else {
    due = std::uint64_t(needed);
    w.accumulator -= double(due) * dt;
  }
  report.initialOverlaps = w.checkInitialOverlaps();
  if (w.profiler.enabled()) w.profiler.resetTotals();
  w.buffers.bindAll();
  for (std::uint64_t i = 0; i < due; ++i) {
    w.emit(dt, &report);
    w.runSubstep();
  }
  report.substeps = std::uint32_t(due);
  report.simulatedTime = float(double(due) * dt);
  if (w.profiler.enabled()) w.profiler.collect();
  if (w.settings.statsEachFrame) {
    report.stats = w.reduceStats();
    report.hasStats = true;
  }
  return report;
}

void World::substep(std::uint32_t count) {
  Impl& w = impl();
  w.gpu->makeCurrent();
  if (count > 0) w.checkInitialOverlaps();
  if (w.profiler.enabled()) w.profiler.resetTotals();
  w.buffers.bindAll();
  for (std::uint32_t i = 0; i < count; ++i) {
    w.emit(w.model.timeStep, nullptr);
    w.runSubstep();
  }
  if (w.profiler.enabled()) w.profiler.collect();
}

std::uint32_t World::bodyCount() const {
  return impl().bodyCount;
}
std::uint32_t World::particleCount() const {
  return impl().particleCount;
}
std::uint32_t World::granulesSpawned() const {
  return impl().granulesSpawned;
}
std::uint32_t World::bodyCapacity() const {
  return impl().bodyCapacity;
}
std::uint32_t World::particleCapacity() const {
  return impl().particleCapacity;
}
std::uint64_t World::stepCount() const {
  return impl().steps;
}
double World::simulatedTime() const {
  return impl().simTime;
}
std::uint64_t World::gpuMemoryBytes() const {
  return impl().buffers.bytes();
}
std::vector<ColliderShape> World::colliders() const {
  return impl().colliderShapes;
}

}  // namespace sandphys
