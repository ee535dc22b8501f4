#include "support/test_world.h"

#include <cmath>

#include "core/world_access.h"
#include "core/world_impl.h"

namespace sandphys::testing {

std::string errorMessageOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const GpuContext& gpu() {
  static GpuContext context = GpuContext::headless();
  return context;
}

void flipVelocityBit(World& world, std::uint32_t body, int axis) {
  gpu().makeCurrent();
  const std::size_t offset = 16 * std::size_t(body) + 4 * std::size_t(axis);
  gl::Buffer& velocity = detail::WorldAccess::impl(world).buffers[detail::kBodyVelocity];
  std::uint32_t bits = 0;
  velocity.download(offset, sizeof bits, &bits);
  bits ^= 1u;
  velocity.upload(offset, sizeof bits, &bits);
  detail::WorldAccess::impl(world).stateChanged();
}

WorldStats reduceStats(World& world) {
  gpu().makeCurrent();
  return detail::WorldAccess::impl(world).reduceStats();
}

std::uint64_t statsReductions(World& world) {
  return detail::WorldAccess::impl(world).statsReductions;
}

void scanEveryChunk(World& world) {
  detail::WorldAccess::impl(world).scanEveryChunk = true;
}

void countEveryPair(World& world) {
  detail::WorldAccess::impl(world).countEveryPair = true;
}

void searchEveryParticle(World& world) {
  gpu().makeCurrent();
  World::Impl& w = detail::WorldAccess::impl(world);
  w.kernels.release();
  w.kernels.compile(w.settings.contactLaw, w.sleep.enabled,
                    w.settings.material.rollingFriction > 0.0f, w.sortsGranules(), true);
  // Without sleep the list build lists the particles the search takes: the next substep builds.
  w.listsStale = true;
}

namespace {

// The fourth uint of a pass's command is its list's length.
std::uint32_t activeListLength(World& world, detail::ActivePass pass) {
  gpu().makeCurrent();
  const std::size_t offset = detail::activeDispatchOffset(pass) + 12;
  std::uint32_t count = 0;
  detail::WorldAccess::impl(world).buffers[detail::kCounters].download(offset, sizeof count,
                                                                       &count);
  return count;
}

}  // namespace

std::uint32_t particlesLeftToSearch(World& world) {
  return activeListLength(world, detail::kActivePassSearch);
}

std::uint32_t particlesLeftToColliders(World& world) {
  return activeListLength(world, detail::kActivePassColliders);
}

void useOneGrid(World& world) {
  World::Impl& w = detail::WorldAccess::impl(world);
  w.oneGrid = true;
  w.paramsDirty = true;
}

void sortGranulesNow(World& world) {
  gpu().makeCurrent();
  World::Impl& w = detail::WorldAccess::impl(world);
  w.buffers.bindAll();
  if (w.sleep.enabled) {
    w.prepareActiveAndSort();
  } else {
    w.prepareContactsAndSort();
  }
}

std::vector<ContactRecord> contactsFromBothSides(World& world) {
  World::Impl& w = detail::WorldAccess::impl(world);
  return w.listContacts(0, w.particleCount, 0.0f, true);
}

WorldSettings smallSettings(std::uint32_t maxBodies) {
  WorldSettings s;
  s.maxBodies = maxBodies;
  s.maxColliders = 16;
  s.statsEachFrame = false;
  return s;
}

void buildPile(World& w) {
  w.addCollider(Plane{});
  w.addCollider(Box{.center = {0, 0.3f, 0}, .halfExtents = {0.1f, 0.3f, 0.1f}, .inside = true});
  w.addGranules(GranuleBlock{.center = {0, 0.12f, 0},
                             .countX = 4,
                             .countY = 6,
                             .countZ = 4,
                             .velocity = {0, -1.5f, 0},
                             .seed = 11});
}

WorldSettings sleepingPileSettings() {
  WorldSettings s = smallSettings();
  s.sleep.enabled = true;
  s.material.rollingFriction = 0.1f;
  return s;
}

TestWorld::TestWorld(const WorldSettings& settings) : m_world(gpu(), settings) {}

ColliderId TestWorld::addFloor(float y, SurfaceMaterial material) {
  return m_world.addCollider(Plane{{0.0f, 1.0f, 0.0f}, y, material});
}

BodyId TestWorld::addGranule(Vec3 position, Quat orientation, Vec3 velocity, Vec3 spin) {
  const auto& s = m_world.settings();
  return m_world.addBody(tetrahedronTemplate(s.particleDiameter, s.material.density),
                         {position, orientation, velocity, spin, Motion::Dynamic});
}

BodyId TestWorld::addSphere(Vec3 position, Vec3 velocity) {
  const auto& s = m_world.settings();
  return m_world.addBody(
      makeParticleTemplate({{0.0f, 0.0f, 0.0f}}, s.particleDiameter, s.material.density),
      {position, {}, velocity, {}, Motion::Dynamic});
}

void TestWorld::simulate(double seconds) {
  const auto steps = std::uint32_t(std::llround(seconds / m_world.timeStep()));
  m_world.substep(steps);
}

}  // namespace sandphys::testing
