// World's colliders and sinks: the descriptors checked and packed for the GPU (gpu_layout.h),
// added, changed or moved, and the sleeping sand they reach woken.
#include "sandphys/world.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <variant>

#include "core/collider_bounds.h"
#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"
#include "gl/gl_check.h"

namespace sandphys {

using namespace detail;

namespace {

using detail::toGpu;  // beside the collider overloads below

// A granule whose centre is this many diameters from a collider's surface may touch it: a
// particle's radius plus the granule's bounding radius, with room to spare.
constexpr float kColliderWakeMargin = 2.0f;

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
  // Only the particles a list build found near a collider run the collider code (contacts.comp):
  // the next substep builds the lists again.
  if (collidersInOwnPass()) listsStale = true;
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
  markBodiesChanged(0, bodyCount);  // the sleepers it woke are computed again
  gl::check("waking a region");
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
  return (to - from) / seconds;
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
  Quat d = to * conjugate(from);
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

}  // namespace sandphys
