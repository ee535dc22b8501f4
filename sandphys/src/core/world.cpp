// A World's life: creation (its settings checked, kernels compiled, buffers allocated), the
// accessors, growing its capacities. Bodies, colliders, snapshots, the step and the statistics
// have files of their own (world_bodies.cpp, world_colliders.cpp, world_snapshots.cpp,
// world_step.cpp, world_stats.cpp).
#include "sandphys/world.h"

#include <algorithm>
#include <string>

#include "core/validation.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

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
  kernels.compile(settings.contactLaw, sleep.enabled, keepsRollingHistory(), sortsGranules());
  buffers.allocate(bodyCapacity, particleCapacity, tableCapacity, settings.maxColliders, 0, 0,
                   keepsHistory(), keepsRollingHistory(), sleep.enabled, sortsGranules());
  profiler.setEnabled(settings.profileKernels);
  uploadParams();
}

World::Impl::~Impl() {
  gpu->makeCurrent();
  kernels.release();
}

// --- World ------------------------------------------------------------------------------------

void World::checkSettings(const WorldSettings& settings) {
  const ContactModel model = ContactModel::fromSettings(settings);
  (void)SleepModel::fromSettings(settings, model.timeStep);
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

void World::reserve(std::uint32_t maxBodies, std::uint32_t maxParticles) {
  Impl& w = impl();
  require(maxParticles <= kMaxParticleCapacity, "World::reserve maxParticles", maxParticles,
          "must be <= " + std::to_string(kMaxParticleCapacity) + " (GPU buffer limit)");
  w.gpu->makeCurrent();
  w.bodyCapacity = std::max(w.bodyCapacity, maxBodies);
  w.particleCapacity = std::max(w.particleCapacity, maxParticles);
  w.tableCapacity = HashTable::sizeFor(w.particleCapacity);
  w.buffers.allocate(w.bodyCapacity, w.particleCapacity, w.tableCapacity, w.settings.maxColliders,
                     w.bodyCount, w.particleCount, w.keepsHistory(), w.keepsRollingHistory(),
                     w.sleep.enabled, w.sortsGranules());
  w.paramsDirty = true;
  // A grown table, and grown lists, are new, empty buffers.
  w.gridValid = false;
  w.listsStale = true;
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
std::vector<BufferMemory> World::gpuMemoryByBuffer() const {
  return impl().buffers.byBuffer();
}
std::vector<ColliderShape> World::colliders() const {
  return impl().colliderShapes;
}

}  // namespace sandphys
