// The step (docs/architecture.md): the passes of one substep in order, all on the GPU. Nothing
// here reads GPU memory; the only CPU work is a fixed number of dispatches per substep (plus the
// upload of what the CPU changed: granules that emitters add, bodies set from outside).
#include <algorithm>
#include <string>

#include "core/assert.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

void World::Impl::uploadParams() {
  stateChanged();
  SimParams p{};
  p.gravity = settings.gravity;
  p.dt = model.timeStep;
  const float skin = model.listSkin;
  const float reach = settings.particleDiameter + skin;
  p.particleRadius = model.radius;
  p.particleDiameter = settings.particleDiameter;
  p.inverseCellSize = 1.0f / reach;
  p.maxOverlap = model.maxOverlap;
  // A build (a marking of the near part) is asked for a hair before a particle has moved half the
  // skin (near skin), so that rounding cannot bring an unlisted (unmarked) pair into contact.
  const auto halfSkinSquared = [](float s) { return 0.98f * 0.25f * s * s; };
  p.listReachSquared = reach * reach;
  p.listMoveSquared = halfSkinSquared(skin);
  const float nearReach = settings.particleDiameter + model.listNearSkin;
  p.nearReachSquared = nearReach * nearReach;
  p.nearMoveSquared = halfSkinSquared(model.listNearSkin);
  // Entries follow the particles in use (every change of their number asks for a build), so
  // that a World with room to spare lays its lists out as a full one does.
  p.listStride = particleCount;
  p.grainStiffness = model.stiffnessGrain;
  p.grainDamping = model.dampingFactorGrain;
  p.friction = settings.material.friction;
  p.tangentialDamping = model.tangentialDamping;
  p.wallStiffness = model.stiffnessWall;
  p.maxSpeed = settings.maxSpeed;
  p.particleCount = particleCount;
  p.bodyCount = bodyCount;
  p.hashMask = table.size - 1u;
  p.sinkCount = std::uint32_t(sinks.size());
  p.hashSize = table.size;
  p.hashMultiplierY = table.multiplierY;
  p.hashMultiplierZ = table.multiplierZ;
  // Colliders go to the GPU sorted by type (stable), so that kernels loop over one type at a time.
  std::vector<GpuCollider> sorted;
  sorted.reserve(colliders.size());
  std::uint32_t ends[3] = {};
  for (std::uint32_t type = kColliderPlane; type <= kColliderRevolution; ++type) {
    for (const GpuCollider& c : colliders) {
      if (std::uint32_t(c.material.x) == type) sorted.push_back(c);
    }
    ends[type - kColliderPlane] = std::uint32_t(sorted.size());
  }
  p.planesEnd = ends[0];
  p.boxesEnd = ends[1];
  p.revolutionsEnd = ends[2];
  p.grainShearStiffness = model.shearStiffnessGrain;
  p.wallShearStiffness = model.shearStiffnessWall;
  p.sleepLinearSpeed = sleep.linearSpeed;
  p.sleepAngularSpeed = sleep.angularSpeed;
  p.wakeAcceleration = sleep.wakeAcceleration;
  p.sleepSubsteps = sleep.substeps;
  p.sleepNeighbourLead = sleep.neighbourLead;
  p.oneGrid = oneGrid ? 1u : 0u;
  p.rollingFriction = settings.material.rollingFriction;
  buffers[kColliders].upload(0, sorted.size() * sizeof(GpuCollider), sorted.data());
  buffers.params.upload(0, sizeof p, &p);
  paramsDirty = false;
}

void World::Impl::dispatch(GLuint program, const char* name, std::uint32_t threads,
                           std::uint32_t groupSize) {
  if (threads == 0) return;
  glUseProgram(program);
  // Large dispatches spill into y (threadIndex() in layout.glsl folds them back).
  std::uint32_t groups = (threads + groupSize - 1) / groupSize;
  constexpr std::uint32_t kMaxX = 32768;
  std::uint32_t gx = std::min(groups, kMaxX);
  std::uint32_t gy = (groups + gx - 1) / gx;
  if (name) profiler.begin(name);
  glDispatchCompute(gx, gy, 1);
  if (name) profiler.end();
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void World::Impl::dispatchIndirect(GLuint program, const char* name, std::uint32_t commandOffset) {
  glUseProgram(program);
  profiler.begin(name);
  glDispatchComputeIndirect(GLintptr(commandOffset));
  profiler.end();
  // Passes over lists write the commands of later passes (contacts, integrate_bodies).
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void World::Impl::markParticlesDirty(std::uint32_t first, std::uint32_t end) {
  stateChanged();
  dirtyParticles.add(first, end);
}

void World::Impl::markBodiesChanged(std::uint32_t first, std::uint32_t end) {
  stateChanged();
  changedBodies.add(first, end);
}

void World::Impl::fitTable() {
  if (HashTable::sizeFor(particleCount) == table.size) return;
  // Buckets past the smaller table hold no count: grid_scatter takes every count back to zero.
  table = HashTable::forParticles(particleCount);
  paramsDirty = true;
  listsStale = true;
}

void World::Impl::prepareBodies() {
  fitTable();
  if (paramsDirty) uploadParams();
  if (scanEveryChunk) markBodiesChanged(0, bodyCount);
  if (sleep.enabled && !changedBodies.empty()) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // after the passes that wrote it
    const std::uint32_t first = changedBodies.begin / kCollectChunk;
    const std::uint32_t end = (changedBodies.end + kCollectChunk - 1) / kCollectChunk;
    buffers[kQuietChunks].zero(4ull * first, 4ull * (end - first));
  }
  changedBodies.clear();
  // 0. The particles of bodies the CPU set, from their bodies (eq. 7, 8); the integration writes
  // the others'.
  writeDirtyParticles("bodies_to_particles");
  // The CPU asks for a list build when it changed the bodies (added, restored) or the table.
  if (listsStale) {
    buffers[kCounters].upload(4 * kCounterListRequested, 4, &kListRequestAll);
    listsStale = false;
    pairsStale = true;
  }
}

void World::Impl::writeDirtyParticles(const char* name) {
  if (dirtyParticles.empty()) return;
  const std::uint32_t count = dirtyParticles.end - dirtyParticles.begin;
  glUseProgram(kernels.bodiesToParticles);
  glUniform2ui(0, dirtyParticles.begin, count);
  dispatch(kernels.bodiesToParticles, name, count, kWorkgroupSize);
  dirtyParticles.clear();
}

void World::Impl::buildLists() {
  // A build marks the particles of dead bodies, which the statistics then leave out.
  stateChanged();
  // 2. The build, in passes whose group counts the decision wrote (zero when not due): the
  // extent of the sand the grid is fitted to (when it builds every grid), bucket counts, their
  // prefix sum (blocks of 1024), scatter into buckets, id order inside each bucket, then each
  // particle's list.
  dispatchIndirect(kernels.gridExtent, "grid_extent", listDispatchOffset(kPassGridExtent));
  dispatchIndirect(kernels.gridCount, "grid_count", listDispatchOffset(kPassGridCount));
  dispatchIndirect(kernels.scanBlocks, "scan_blocks", listDispatchOffset(kPassScanBlocks));
  dispatchIndirect(kernels.scanBlockSums, "scan_block_sums",
                   listDispatchOffset(kPassScanBlockSums));
  dispatchIndirect(kernels.scanAdd, "scan_add", listDispatchOffset(kPassScanAdd));
  dispatchIndirect(kernels.gridScatter, "grid_scatter", listDispatchOffset(kPassGridScatter));
  dispatchIndirect(kernels.gridSort, "grid_sort", listDispatchOffset(kPassGridSort));
  dispatchIndirect(kernels.listBuild, "list_build", listDispatchOffset(kPassListBuild));
  gridValid = true;
}

void World::Impl::prepareContacts() {
  prepareBodies();
  // 1. Build the neighbour lists or not: the GPU decides (a particle moved half the skin, a
  // granule died, the CPU asked).
  dispatch(kernels.listCheck, "list_check", 1, 1);
  buildLists();
  // 2b. Without sleep, the lists' near part marked again: after a build, or once a particle moved
  // half the near skin (list_check decides that too).
  if (kernels.listNear) {
    dispatchIndirect(kernels.listNear, "list_near", listDispatchOffset(kPassListNear));
  }
}

void World::Impl::prepareActive() {
  // With sleep: the bodies and particles this substep computes, the awake ones and the sleepers
  // something awake touched (and the list decision, in the same pass); the passes after it run
  // over them alone, from indirect commands.
  prepareBodies();
  dispatch(kernels.collectActive, "collect_active", (bodyCount + kCollectChunk - 1) / kCollectChunk,
           kWorkgroupSize);
  buildLists();
}

void World::Impl::searchContacts() {
  // 3b. The same for the particles whose partners are not all in their lists, which the contacts
  // passes left to this one: they search the grid (none in most substeps: an empty dispatch);
  // and for those with more contact slots in use than the other passes load.
  dispatchIndirect(kernels.contactsSearch, "contacts_search",
                   activeDispatchOffset(kActivePassSearch));
}

void World::Impl::runSubstep() {
  stateChanged();
  bodyForcesClear = false;
  const bool sleeping = sleep.enabled && bodyCount > 0;
  if (sleeping) {
    if (granuleSortDue()) {
      prepareActiveAndSort();
    } else {
      prepareActive();
    }
  } else {
    if (granuleSortDue()) {
      prepareContactsAndSort();
    } else {
      prepareContacts();
    }
  }
  // The first substep after the bodies changed or were restored takes every granule's pair counts
  // (a read-back's list build in between must not take that from it: the CPU says it, not the
  // build).
  const std::uint32_t recount = pairsStale || countEveryPair ? 1u : 0u;
  if (recount) buffers[kCounters].upload(4 * kCounterRecountPairs, 4, &recount);
  if (sleeping) {
    // 3, 4 as below.
    dispatchIndirect(kernels.contacts, "contacts", activeDispatchOffset(kActivePassContacts));
    searchContacts();
    dispatchIndirect(kernels.integrateBodies, "integrate_bodies",
                     activeDispatchOffset(kActivePassBodies));
  } else {
    // 3. Contact forces (eq. 9, 10) from the lists, and colliders, gathered per particle.
    dispatch(kernels.contacts, "contacts", particleCount, kWorkgroupSize);
    if (collidersInOwnPass()) {
      // 3c. The particles whose list's build found a collider near, which the contacts pass left
      // to this one: the collider code runs for them alone. Before the search's pass, which
      // takes the particles with more contact slots in use than this one loads.
      dispatchIndirect(kernels.contactsColliders, "contacts_colliders",
                       activeDispatchOffset(kActivePassColliders));
    }
    searchContacts();
    // 4. Body sums (eq. 2, 3) and integration (eq. 4-6), guards, sinks; the particles of the
    // next substep.
    dispatch(kernels.integrateBodies, "integrate_bodies", bodyCount, kWorkgroupSize);
  }
  // 4b. Every other body: a workgroup each (force sums for read-back, then the same integration);
  // with sleep a workgroup for each entry of the active list, the rest return at once.
  if (!largeBodies.empty()) {
    dispatch(kernels.integrateLargeBodies, "integrate_large_bodies",
             std::uint32_t(largeBodies.size()) * kWorkgroupSize, kWorkgroupSize);
  }
  // 5. HertzMindlin: the pair counts of the granules whose slots changed (listed by 4).
  if (kernels.countPairs) {
    dispatchIndirect(kernels.countPairs, "count_pairs", activeDispatchOffset(kActivePassPairs));
  }
  if (recount) {
    const std::uint32_t done = 0;
    buffers[kCounters].upload(4 * kCounterRecountPairs, 4, &done);
    pairsStale = false;
  }
  advanceClock();
}

void World::Impl::advanceClock() {
  ++steps;
  simTime += model.timeStep;
}

void World::Impl::emit(double dt, StepReport* report) {
  for (auto& emitter : emitters) {
    if (!emitter || emitter->finished()) continue;
    bool blocked = false;
    const auto perGranule = std::uint32_t(granule.offsets.size());
    const std::uint32_t room =
        std::min(bodyCapacity - bodyCount, (particleCapacity - particleCount) / perGranule);
    auto spawns = emitter->advance(dt, room, blocked);
    // step() does not throw: addBodies must find the room it counts.
    SANDPHYS_ASSERT(spawns.size() <= room, "an emitter spawned " + std::to_string(spawns.size()) +
                                               " granules with room for " + std::to_string(room));
    if (!spawns.empty()) {
      std::vector<BodyDesc> descs;
      descs.reserve(spawns.size());
      for (const auto& s : spawns)
        descs.push_back({s.position, s.orientation, s.velocity, {}, Motion::Dynamic});
      const std::uint32_t firstBody = addBodies(granule, descs, true);
      checkSpawnPlaces(firstBody, std::uint32_t(descs.size()));
      if (report) report->granulesEmitted += std::uint32_t(spawns.size());
    }
    if (blocked && report) report->emitterBlocked = true;
  }
}

void World::Impl::checkSpawnPlaces(std::uint32_t firstBody, std::uint32_t count) {
  // The grid is the last list build's; without one (a new or just restored World) nothing is
  // checked.
  if (count == 0 || !gridValid) return;
  if (paramsDirty) uploadParams();
  buffers.bindAll();
  const std::uint32_t firstParticle = particleEnd(firstBody) - granule.offsets.size();
  const auto particles = std::uint32_t(count * granule.offsets.size());
  glUseProgram(kernels.spawnCheck);
  glUniform2ui(0, firstParticle, particles);
  dispatch(kernels.spawnCheck, "spawn_check", particles, kWorkgroupSize);
}

}  // namespace sandphys
