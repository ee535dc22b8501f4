#pragma once

#include <sandphys/sandphys.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sandphys::testing {

/// The message of the sandphys::Error that `call` throws, or "no error" when it throws none; any
/// other exception (std::bad_alloc, say) reaches GoogleTest and fails the test.
std::string errorMessageOf(const std::function<void()>& call);

/// The one headless GL context of a test process (created on first use).
const GpuContext& gpu();

/// Flips the lowest bit of body slot `body`'s velocity component `axis` in the GPU's own buffer:
/// a change of one unit in the last place that no public call could make without rounding.
void flipVelocityBit(World& world, std::uint32_t body, int axis);

/// Makes every list build of a sleeping World sort every particle into one grid and leave the
/// still grid empty (World::Impl::oneGrid): the oracle of its two grids.
void useOneGrid(World& world);

/// Makes collect_active.comp of a sleeping `world` scan every chunk of bodies in every substep
/// (World::Impl::scanEveryChunk), not only those something may have changed since it found them
/// quiet: the oracle of the latter.
void scanEveryChunk(World& world);

/// The statistics reduced from every particle and body now (World::Impl::reduceStats), never
/// those of the last reduce kept while nothing changed: the oracle of the latter.
WorldStats reduceStats(World& world);

/// How many times `world` has reduced its statistics on the GPU.
std::uint64_t statsReductions(World& world);

/// Makes every substep of `world` take every granule's pair counts (World::Impl::countEveryPair),
/// not only those whose contact slots changed: the oracle of the latter.
void countEveryPair(World& world);

/// Makes the contacts pass of `world` leave every particle to the grid search (SEARCH_EVERY in
/// contacts.comp), not only those beyond a full list or with a list a build passed over: the
/// oracle of the latter.
void searchEveryParticle(World& world);

/// How many particles the contacts pass of the last substep left to the grid search.
std::uint32_t particlesLeftToSearch(World& world);

/// How many particles the contacts pass of the last substep left to the pass with the collider
/// code: those a list build found near a collider, and those with more contact slots in use than
/// the contacts pass loads.
std::uint32_t particlesLeftToColliders(World& world);

/// Sorts the granules of `world` by place now (World::Impl::prepareContactsAndSort, with sleep
/// prepareActiveAndSort), as a substep after a multiple of WorldSettings::sortInterval does before
/// its contacts; `world` must sort. With sleep that lists what the substep computes, as a
/// substep does: the sleepers that something touched are not listed in the next one.
void sortGranulesNow(World& world);

/// Every contact of `world` from each of its particles' sides (World::readContacts gives a pair
/// once, from its lower particle's side).
std::vector<ContactRecord> contactsFromBothSides(World& world);

/// Settings for small test scenes: default material, capacity for `maxBodies` bodies.
WorldSettings smallSettings(std::uint32_t maxBodies = 256);

/// The small pile of the determinism and sleep tests: 96 granules dropped at 1.5 m/s into a
/// 0.2 m box on a floor plane; it settles well within a second of simulated time.
void buildPile(World& world);

/// smallSettings with sleep and rolling friction, for tests that need buildPile's pile to fall
/// asleep whole: with rolling friction it did so on every trajectory tried (the last bits that a
/// sort of the granules, or any change to a kernel, moves). Without, a granule can rock on two
/// contacts for ever (docs/architecture.md, "What keeps a settled pile awake").
WorldSettings sleepingPileSettings();

/// A world with helpers in the manner of Chrono's DEM unit tests: build the scene in a line each,
/// then simulate(seconds).
class TestWorld {
 public:
  explicit TestWorld(const WorldSettings& settings = smallSettings());

  World& operator*() { return m_world; }
  World* operator->() { return &m_world; }

  /// A smooth floor plane at height y (m).
  ColliderId addFloor(float y = 0.0f, SurfaceMaterial material = {});
  /// One granule at `position` with the given orientation, velocity and spin.
  BodyId addGranule(Vec3 position, Quat orientation = {}, Vec3 velocity = {}, Vec3 spin = {});
  /// One body of a single particle (a sphere of the world's particle diameter).
  BodyId addSphere(Vec3 position, Vec3 velocity = {});
  /// Runs whole substeps for `seconds` of simulated time.
  void simulate(double seconds);

 private:
  World m_world;
};

}  // namespace sandphys::testing
