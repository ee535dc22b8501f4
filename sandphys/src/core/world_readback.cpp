// Read-back: every function here waits for the GPU (a sync point) and is meant for analysis,
// tests and debugging, never for every substep.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <tuple>

#include "core/assert.h"
#include "core/contact_state.h"
#include "core/log.h"
#include "core/world_impl.h"
#include "gl/gl_check.h"

namespace sandphys {

using namespace detail;

namespace {

Quat fromGpu(const GpuVec4& q) {
  return {q.w, q.x, q.y, q.z};
}
Vec3 xyz(const GpuVec4& v) {
  return {v.x, v.y, v.z};
}

// Every body slot in use, as the GPU stores it.
struct StoredBodies {
  std::vector<GpuVec4> position, orientation, velocity, spin;
  std::vector<GpuUVec4> info;
};

StoredBodies downloadBodies(const World::Impl& w, const char* call) {
  w.gpu->makeCurrent();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  StoredBodies b{w.buffers[kBodyPosition].downloadArray<GpuVec4>(w.bodyCount),
                 w.buffers[kBodyOrientation].downloadArray<GpuVec4>(w.bodyCount),
                 w.buffers[kBodyVelocity].downloadArray<GpuVec4>(w.bodyCount),
                 w.buffers[kBodyAngularVelocity].downloadArray<GpuVec4>(w.bodyCount),
                 w.buffers[kBodyInfo].downloadArray<GpuUVec4>(w.bodyCount)};
  gl::check(call);
  return b;
}

}  // namespace

std::vector<BodyState> World::readBodies() const {
  const Impl& w = impl();
  const StoredBodies stored = downloadBodies(w, "World::readBodies");
  std::vector<BodyState> out(w.bodyCount);
  for (std::uint32_t i = 0; i < w.bodyCount; ++i) {
    const BodyId id = w.bodyId(i);
    BodyState& s = out[id.index];
    s.id = id;
    s.position = xyz(stored.position[i]);
    s.orientation = fromGpu(stored.orientation[i]) * conjugate(w.principalRotations[i]);
    s.velocity = xyz(stored.velocity[i]);
    s.angularVelocity = xyz(stored.spin[i]);
    s.alive = (stored.info[i].z & kBodyAlive) != 0;
    s.granule = (stored.info[i].z & kBodyGranule) != 0;
    s.motion = w.bodyMotions[i];
  }
  return out;
}

WorldSnapshot World::readSnapshot() const {
  const Impl& w = impl();
  const StoredBodies stored = downloadBodies(w, "World::readSnapshot");
  WorldSnapshot snapshot;
  snapshot.steps = w.steps;
  snapshot.simulatedTime = w.simTime;
  snapshot.unsteppedTime = w.accumulator;
  snapshot.heldSubsteps = w.heldSubsteps;
  snapshot.bodies.resize(w.bodyCount);
  for (std::uint32_t i = 0; i < w.bodyCount; ++i) {
    const GpuVec4& p = stored.position[i];
    const GpuVec4& q = stored.orientation[i];
    const GpuVec4& v = stored.velocity[i];
    const GpuVec4& omega = stored.spin[i];
    StoredBody& b = snapshot.bodies[i];
    b.position = {p.x, p.y, p.z};
    b.principalOrientation = fromGpu(q);
    b.velocity = {v.x, v.y, v.z};
    b.angularVelocity = {omega.x, omega.y, omega.z};
    b.alive = (stored.info[i].z & kBodyAlive) != 0;
    b.calm = std::bit_cast<std::uint32_t>(v.w);
  }
  const std::span<const std::uint32_t> ids = w.slotIds();
  snapshot.bodyIds.assign(ids.begin(), ids.end());
  if (w.keepsHistory()) snapshot.contacts = downloadContacts(w.buffers, w.particleCount);
  if (w.keepsRollingHistory()) snapshot.rolling = downloadRolling(w.buffers, w.particleCount);
  if (w.sleep.enabled) snapshot.forces = downloadForces(w.buffers, w.particleCount);
  return snapshot;
}

std::uint64_t World::readStateHash() {
  Impl& w = impl();
  w.gpu->makeCurrent();
  if (w.paramsDirty) w.uploadParams();
  w.buffers.bindAll();
  glUseProgram(w.kernels.stateHash);
  glDispatchCompute(kStatsWorkgroups, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::array<std::uint32_t, 2 * kStatsWorkgroups> partials{};
  w.buffers[kStateHashPartials].download(0, sizeof partials, partials.data());
  gl::check("World::readStateHash");
  // Integer sums: the same total whatever order the workgroups ran in.
  std::uint32_t low = 0;
  std::uint32_t high = 0;
  for (std::uint32_t g = 0; g < kStatsWorkgroups; ++g) {
    low += partials[2 * g];
    high += partials[2 * g + 1];
  }
  return (std::uint64_t(high) << 32) | low;
}

BodyState World::readBody(BodyId id) const {
  impl().requireBody(id);
  // Small scenes only call this; reading one row of each buffer would be faster for huge ones.
  return readBodies()[id.index];
}

std::vector<ParticleState> World::readParticles() const {
  const Impl& w = impl();
  w.gpu->makeCurrent();
  // Bodies placed since the last substep: their particles as the next substep will start from
  // them (not profiled: no step's work).
  if (!w.dirtyParticles.empty()) {
    Impl& writable = const_cast<Impl&>(w);
    if (writable.paramsDirty) writable.uploadParams();
    writable.buffers.bindAll();
    writable.writeDirtyParticles(nullptr);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  auto owner = w.buffers[kParticleBody].downloadArray<std::uint32_t>(w.particleCount);
  auto position = w.buffers[kParticlePosition].downloadArray<GpuVec4>(w.particleCount);
  auto velocity = w.buffers[kParticleVelocity].downloadArray<GpuVec4>(w.particleCount);
  auto force = w.buffers[kParticleForce].downloadArray<GpuVec4>(w.particleCount);
  gl::check("World::readParticles");
  std::vector<ParticleState> out(w.particleCount);
  for (std::uint32_t i = 0; i < w.particleCount; ++i) {
    out[i] = {w.bodyId(owner[i]), xyz(position[i]), xyz(velocity[i]), xyz(force[i])};
  }
  return out;
}

std::vector<ContactRecord> World::Impl::listContacts(std::uint32_t first, std::uint32_t end,
                                                     float minOverlap, bool bothSides) {
  gpu->makeCurrent();
  // Each particle has at most ~12 neighbours in a packing (tetrahedral granules a few more) plus
  // a few walls; grow and retry if a pile ever has more. A tolerance keeps only a few.
  std::uint32_t capacity =
      std::max<std::uint32_t>(1024u, (minOverlap > 0.0f ? 1u : 8u) * (end - first));
  for (;;) {
    gl::Buffer& list = buffers[kContactList];
    const std::size_t bytes =
        kContactListHeaderBytes + std::size_t(capacity) * sizeof(GpuContactRecord);
    if (list.size() < bytes) list = gl::Buffer(bytes, kGpuBuffers[kContactList].array);
    std::uint32_t header[4] = {0u, capacity, 0u, 0u};
    static_assert(sizeof header == kContactListHeaderBytes);
    list.upload(0, sizeof header, header);
    buffers.bindAll();
    // What the next substep does first: lists built if due (that changes nothing it computes).
    prepareContacts();
    glUseProgram(kernels.contactList);
    glUniform1ui(0, first);
    glUniform1f(1, minOverlap);
    glUniform1ui(2, bothSides ? 1u : 0u);
    dispatch(kernels.contactList, "contact_list", end - first, kWorkgroupSize);
    std::uint32_t count = 0;
    list.download(0, 4, &count);
    if (count > capacity) {
      capacity = count;
      continue;
    }
    std::vector<GpuContactRecord> raw(count);
    list.download(kContactListHeaderBytes, count * sizeof(GpuContactRecord), raw.data());
    gl::check("listing contacts");
    std::vector<ContactRecord> out(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      const auto& r = raw[i];
      const bool withCollider = r.particleB == ContactRecord::kNone;
      SANDPHYS_ASSERT(!withCollider || r.collider < colliders.size(),
                      "contact_list names collider " + std::to_string(r.collider) + " of " +
                          std::to_string(colliders.size()));
      out[i] = {r.particleA,
                r.particleB,
                bodyId(r.bodyA),
                withCollider ? BodyId{} : bodyId(r.bodyB),
                withCollider ? ColliderId{r.collider} : ColliderId{},
                {r.px, r.py, r.pz},
                {r.nx, r.ny, r.nz},
                r.normalForce,
                {r.tx, r.ty, r.tz},
                r.overlap,
                {r.sx, r.sy, r.sz},
                {r.rollingTorqueX, r.rollingTorqueY, r.rollingTorqueZ},
                {r.rollingSpringX, r.rollingSpringY, r.rollingSpringZ}};
    }
    // Appends happen in thread order: sort so that the list is the same on every call.
    std::sort(out.begin(), out.end(), [](const ContactRecord& a, const ContactRecord& b) {
      return std::tie(a.particleA, a.particleB, a.collider.index) <
             std::tie(b.particleA, b.particleB, b.collider.index);
    });
    return out;
  }
}

std::vector<ContactRecord> World::readContacts() const {
  impl();  // throws for a moved-from World; the contact pass is GPU work, not a change
  return m_impl->listContacts(0, m_impl->particleCount, 0.0f, false);
}

InitialOverlaps World::Impl::checkInitialOverlaps() {
  InitialOverlaps result;
  if (overlapCheckEnd <= overlapCheckBegin) return result;
  const float tolerance = kInitialOverlapTolerance * settings.particleDiameter;
  const std::vector<ContactRecord> deep =
      listContacts(overlapCheckBegin, overlapCheckEnd, tolerance, true);
  overlapCheckBegin = overlapCheckEnd = 0;
  std::vector<std::uint32_t> particles;
  for (const ContactRecord& c : deep) {
    particles.push_back(c.particleA);
    if (c.overlap > result.worstOverlap) {
      result.worstOverlap = c.overlap;
      result.body = c.bodyA;
      result.otherBody = c.bodyB;
      result.collider = c.collider;
    }
  }
  particles.erase(std::unique(particles.begin(), particles.end()), particles.end());
  result.particles = std::uint32_t(particles.size());
  if (result.particles > 0) {
    const double d = settings.particleDiameter;
    char message[400];
    std::snprintf(message, sizeof message,
                  "%u particles of the bodies added before this step start overlapping by more "
                  "than %.3g d (worst %.3g d: body %u with %s %u); contacts push them apart at "
                  "once, with the energy of the overlap. Place them apart "
                  "(StepReport::initialOverlaps has the numbers).",
                  result.particles, double(kInitialOverlapTolerance), result.worstOverlap / d,
                  result.body.index, result.collider.isValid() ? "collider" : "body",
                  result.collider.isValid() ? result.collider.index : result.otherBody.index);
    log(LogLevel::Warning, message);
  }
  return result;
}

Vec3 BodyForce::meanForce() const {
  const float n = substeps > 0 ? float(substeps) : 1.0f;
  return {force.x / n, force.y / n, force.z / n};
}

Vec3 BodyForce::meanTorque() const {
  const float n = substeps > 0 ? float(substeps) : 1.0f;
  return {torque.x / n, torque.y / n, torque.z / n};
}

std::vector<BodyForce> World::takeBodyForces() {
  Impl& w = impl();
  std::vector<BodyForce> out;
  if (w.largeBodies.empty()) return out;
  const auto count = std::uint32_t(w.largeBodies.size());
  std::vector<GpuVec4> sums(2 * count);
  if (!w.bodyForcesClear) {
    w.gpu->makeCurrent();
    sums = w.buffers[kLargeBodyForces].downloadArray<GpuVec4>(2 * count);
    w.buffers[kLargeBodyForces].zero();
    w.bodyForcesClear = true;
  }
  out.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t slot = w.largeBodies[i];
    out.push_back({w.bodyId(slot), xyz(sums[2 * i]), xyz(sums[2 * i + 1]),
                   std::uint32_t(std::lround(sums[2 * i].w))});
  }
  return out;
}

std::vector<KernelTime> World::kernelTimes() const {
  std::vector<KernelTime> out;
  for (const auto& t : impl().profiler.totals())
    out.push_back({t.name, t.milliseconds, t.dispatches});
  return out;
}

void World::setProfileKernels(bool enabled) {
  impl().settings.profileKernels = enabled;
  impl().profiler.setEnabled(enabled);
  if (!enabled) impl().profiler.resetTotals();
}

}  // namespace sandphys
