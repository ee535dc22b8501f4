// World's body slots: the storage behind World's bodies (world_bodies.cpp): room counted before
// anything is built, the per-slot data on the CPU and the GPU, ids, and the checks of new bodies.
#include <algorithm>
#include <bit>
#include <string>

#include "core/assert.h"
#include "core/overlap_check.h"
#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

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
  auto nextEntry = std::uint32_t(largeBodies.size());
  for (std::uint64_t i = 0; i < n; ++i) {
    const Motion motion = descs[i].motion;
    const bool dynamic = motion == Motion::Dynamic;
    const std::uint32_t flags =
        kBodyAlive | (isGranule ? kBodyGranule : 0u) |
        (isLarge(descs[i]) ? kBodyLarge | nextEntry++ << kBodyEntryShift : 0u) |
        (std::uint32_t(motion) << kBodyMotionShift);
    info[i] = {std::uint32_t(firstParticle + i * perBody), std::uint32_t(perBody), flags, 0u};
    inertia[i] = toGpu(shape.principalInertia, shape.mass);
    // -1 marks static particles, whose force the contact kernel skips (gpu_buffers.def). The
    // paper's law damps with the particle's share of the mass, HertzMindlin with the body's.
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
  addIds(firstBody, bodyCount);
  generations.resize(bodyCount, 0);
  principalRotations.resize(bodyCount, shape.principalRotation);
  for (const BodyDesc& d : descs) bodyMotions.push_back(d.motion);
  bodyMasses.resize(bodyCount, shape.mass);
  for (std::uint64_t i = 0; i < n; ++i)
    particleEnds.push_back(std::uint32_t(firstParticle + (i + 1) * perBody));
  boundingRadii.resize(bodyCount, shape.boundingRadius);
  uploadBodyStates(firstBody, descs, shape);
  // New particles: their state before the next contacts, and lists that hold them; and new
  // bodies to list, in chunks that may have been found quiet.
  markParticlesDirty(firstParticle, particleCount);
  markBodiesChanged(firstBody, bodyCount);
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
    Quat q = d.orientation * principalRotations[first + i];
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

void World::Impl::placeBody(std::uint32_t body, const BodyDesc& desc) {
  // Inside a step the integration may still be writing the body's state.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  // The body's mass data stay as they were (kept on the CPU: no sync, so a bridge can call this
  // every frame).
  ParticleTemplate massOnly;
  massOnly.mass = bodyMasses[body];
  massOnly.boundingRadius = boundingRadii[body];
  uploadBodyStates(body, {desc}, massOnly);
  // Its particles follow before the next contacts (and ask for a list build if they jumped).
  const std::uint32_t first = body == 0 ? 0u : particleEnd(body - 1);
  markParticlesDirty(first, particleEnd(body));
  // A sleeper placed is computed again: its chunk is scanned.
  markBodiesChanged(body, body + 1);
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

BodyId World::Impl::bodyId(std::uint32_t slot) const {
  SANDPHYS_ASSERT(slot < bodyCount, "body slot " + std::to_string(slot) + " of " +
                                        std::to_string(bodyCount) + " in use");
  const std::uint32_t id = idOf(slot);
  return BodyId{id, generations[id]};
}

void World::Impl::requireBody(BodyId id) const {
  if (!id.isValid() || id.index >= bodyCount || generations[id.index] != id.generation) {
    throw InvalidId("BodyId {index " + std::to_string(id.index) + ", generation " +
                    std::to_string(id.generation) +
                    "} is invalid or stale (bodies: " + std::to_string(bodyCount) + ")");
  }
}

}  // namespace sandphys
