#pragma once

#include <GL/glew.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/collider_bounds.h"
#include "core/emitter.h"
#include "core/gpu_buffers.h"
#include "gl/async_read.h"
#include "gl/buffer.h"
#include "gl/kernel_profiler.h"
#include "sandphys/kinematic_move.h"
#include "sandphys/world.h"

namespace sandphys {

namespace detail {

/// Every GPU buffer of a World, one per attribute (gpu_buffers.def).
struct WorldBuffers {
  std::array<gl::Buffer, kBindingCount> storage;
  gl::Buffer params;  // uniform SimParams
  // Buffer-texture views (View in gpu_buffers.def), indexed by TextureUnit.
  std::array<GLuint, kTextureCount> textures{};

  WorldBuffers() = default;
  ~WorldBuffers();
  WorldBuffers(const WorldBuffers&) = delete;
  WorldBuffers& operator=(const WorldBuffers&) = delete;

  gl::Buffer& operator[](Binding b) { return storage[b]; }
  const gl::Buffer& operator[](Binding b) const { return storage[b]; }

  /// Allocates (or, when already allocated, grows keeping contents) for these capacities;
  /// `history`: the contact law keeps contact state (the contact slots and what goes with them);
  /// `rollingHistory`: it keeps rolling springs too (rolling friction); `sleeping`: sleeping sand
  /// (its lists of what a substep computes, what goes with them, and the list build's second grid:
  /// a moving and a still one, common/grid.glsl); `sorting`: the granules are sorted by place
  /// (the sort's plan).
  void allocate(std::uint32_t bodies, std::uint32_t particles, std::uint32_t tableSize,
                std::uint32_t colliders, std::uint32_t bodiesInUse, std::uint32_t particlesInUse,
                bool history, bool rollingHistory, bool sleeping, bool sorting);
  void bindAll() const;
  /// Each buffer's size, in binding order, then the uniform block's.
  std::vector<BufferMemory> byBuffer() const;
  std::uint64_t bytes() const;
};

/// The compute programs of a World, compiled once.
struct WorldKernels {
  GLuint bodiesToParticles = 0;
  GLuint scanBlocks = 0;
  GLuint scanBlockSums = 0;
  GLuint scanAdd = 0;
  GLuint gridExtent = 0;
  GLuint gridCount = 0;
  GLuint gridScatter = 0;
  GLuint gridSort = 0;
  GLuint listCheck = 0;
  GLuint listBuild = 0;
  GLuint listNear = 0;  // without sleep
  GLuint contacts = 0;
  GLuint contactList = 0;
  GLuint contactsSearch = 0;  // contacts.comp over the particles it left to the grid search
  // contacts.comp over the particles near a collider, which it left to the collider code (without
  // sleep).
  GLuint contactsColliders = 0;
  GLuint integrateBodies = 0;
  GLuint integrateLargeBodies = 0;
  GLuint countPairs = 0;
  GLuint statsReduce = 0;
  GLuint resetPeakOverlap = 0;
  GLuint stateHash = 0;
  GLuint spawnCheck = 0;
  GLuint wakeRegion = 0;     // with sleeping only
  GLuint collectActive = 0;  // with sleeping only
  // The sort of the granules by place (WorldSettings::sortInterval), compiled only with it.
  GLuint orderSequence = 0;
  GLuint orderSources = 0;
  GLuint orderSlots = 0;
  GLuint orderMoves = 0;
  GLuint orderPack = 0;
  GLuint orderGather = 0;
  GLuint orderKeys = 0;

  /// Compiles every kernel for `law` (PAPER_LAW defined for ContactLaw::PaperViscous), with
  /// `sleeping` for sleeping sand (SLEEPING defined), with `rollingFriction` for a non-zero
  /// Material::rollingFriction (ROLLING_FRICTION defined, so that a World without it runs no
  /// code for it); with `searchEvery` (a test's oracle), the contacts pass leaves every particle
  /// to the grid search (SEARCH_EVERY); with `sorting`, the sort of the granules by place.
  void compile(ContactLaw law, bool sleeping, bool rollingFriction, bool sorting,
               bool searchEvery = false);
  void release();
};

/// A kinematic body's move as World::moveKinematic resolved it (world_moves.cpp).
struct KinematicPath {
  std::uint32_t body = 0;  // body slot
  KinematicMove move;      // orientation normalised
  KinematicMovePlan plan;
};

/// Smallest power of two >= 4096 and >= `particles`, with hash multipliers that send the 27
/// cells around any cell to 27 distinct buckets: the GPU's when sand does not fit the table
/// (shaders/sim/common/grid_fit.glsl fits the grid to it). A World allocates the table for its
/// capacity but uses the one for the particles it holds, so that the list builds cost what is in
/// use.
struct HashTable {
  std::uint32_t size = 0;
  std::uint32_t multiplierY = 0;
  std::uint32_t multiplierZ = 0;
  static HashTable forParticles(std::uint32_t particles);
  static std::uint32_t sizeFor(std::uint32_t particles);
};

/// Slots [begin, end) that the CPU changed since the GPU last took them: grown to cover every
/// range added, cleared once taken.
struct ChangedRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  bool empty() const { return end <= begin; }
  void add(std::uint32_t first, std::uint32_t last) {
    if (first >= last) return;
    begin = empty() ? first : std::min(begin, first);
    end = std::max(end, last);
  }
  void clear() { begin = end = 0; }
};

}  // namespace detail

struct World::Impl {
  const GpuContext* gpu = nullptr;
  WorldSettings settings;
  ContactModel model;
  SleepModel sleep;
  ParticleTemplate granule;

  std::uint32_t bodyCapacity = 0;
  std::uint32_t particleCapacity = 0;
  detail::HashTable table;          // in use: for particleCount (fitTable)
  std::uint32_t tableCapacity = 0;  // buckets allocated: for particleCapacity
  std::uint32_t bodyCount = 0;
  std::uint32_t particleCount = 0;
  std::uint32_t granulesSpawned = 0;
  std::vector<std::uint32_t> generations;   // per body id
  std::vector<Quat> principalRotations;     // per body slot: template frame -> principal frame
  std::vector<Motion> bodyMotions;          // per body slot, as added
  std::vector<float> bodyMasses;            // per body slot, kg
  std::vector<float> boundingRadii;         // per body slot, m
  std::vector<std::uint32_t> particleEnds;  // per body slot: one past its last particle
  std::vector<std::uint32_t> largeBodies;   // body slots flagged kBodyLarge (layout.glsl)
  // The ids of the bodies in the slots and the slots of the ids (WorldSettings::sortInterval),
  // as the GPU last held them when not orderStale (a sort ran since, or a restore); both empty
  // while every slot holds the body of its own index (world_order.cpp). The per-slot arrays above
  // are alike for every granule a sort moves, so they stay per slot.
  mutable std::vector<std::uint32_t> idsOfSlots;
  mutable std::vector<std::uint32_t> slotsOfIds;
  mutable bool orderStale = false;
  std::vector<detail::GpuCollider> colliders;
  std::vector<ColliderShape> colliderShapes;  // the descriptors of `colliders`, for renderers
  std::vector<detail::GpuSink> sinks;
  std::vector<std::optional<detail::EmitterState>> emitters;
  // Every body's latest move, kept after it ends: a World restored to a snapshot taken before
  // the end runs it again (world_moves.cpp).
  std::vector<detail::KinematicPath> moves;
  std::uint64_t movesEnd = 0;  // the latest endStep of `moves`

  double accumulator = 0.0;
  // Substeps a frame had due beyond World::step's stopAt, run first by the next call.
  std::uint64_t heldSubsteps = 0;
  std::uint64_t steps = 0;
  double simTime = 0.0;
  bool warnedDroppedTime = false;
  bool paramsDirty = true;
  // The grid buffers hold the grid of the last list build, with the table in use
  // (spawn_check.comp).
  bool gridValid = false;
  // The CPU changed what the lists hold (bodies added or restored, the table or the buffers
  // changed): the next substep builds them.
  bool listsStale = true;
  // The same, for the pair counts of the damping (contact_pairs.glsl): the next substep's
  // integration takes every granule's, not only those whose slots changed (a restored state's
  // counts need not be those of its slots).
  bool pairsStale = true;
  // Every substep takes every granule's pair counts (a test's oracle of taking them only where
  // the slots changed: the counts, and so the results, are the same bit for bit).
  bool countEveryPair = false;
  // With sleep: every build sorts every particle into one grid, the moving grid, and leaves the
  // still grid empty (a test's oracle of the two grids: the lists and so the results are the
  // same bit for bit). Set paramsDirty after changing it.
  bool oneGrid = false;
  // With sleep: every substep scans every chunk (a test's oracle of passing over the quiet ones:
  // the active lists, and so the results, are the same bit for bit).
  bool scanEveryChunk = false;
  // Particles whose state must be written from their bodies before the next contacts (bodies
  // added, set or restored by the CPU).
  detail::ChangedRange dirtyParticles;
  // With sleep: bodies the CPU changed (added, placed, restored, woken), whose chunks of
  // QuietChunks collect_active.comp scans again in the next substep.
  detail::ChangedRange changedBodies;
  // Particles of bodies the CPU added since the last step, checked for deep initial overlaps at
  // its start: [overlapCheckBegin, overlapCheckEnd).
  std::uint32_t overlapCheckBegin = 0;
  std::uint32_t overlapCheckEnd = 0;
  // With sleep: the last substep the CPU saw counted (reduceStats, or a step's check) computed
  // nothing: the next step checks its first substep and skips the rest if it computed nothing
  // either (world_step.cpp).
  bool sandLooksIdle = false;
  // The statistics of the last reduce (reduceStats), and the counters it or a step's check last
  // downloaded. statsCurrent while what the reduce read is as it was then: no substep has computed
  // anything or built lists since, and the CPU has changed no body, particle or parameter
  // (stateChanged). A frame of sleeping sand then reads them instead of every particle again.
  WorldStats reducedStats;
  std::array<std::uint32_t, detail::kCounterCount> counters{};
  bool statsCurrent = false;
  std::uint64_t statsReductions = 0;  // reduceStats calls, for the tests of the above
  // Every particle's largest overlap is zero: reset, and nothing computed since.
  bool peaksClear = false;
  // The large bodies' force sums are zero: taken (World::takeBodyForces) and no substep run since,
  // so the next take reads nothing back (frames of sleeping sand run none).
  bool bodyForcesClear = false;
  // A step's check found that the last substep run computed nothing, and nothing has changed
  // since: the substeps that follow would compute nothing either, until the CPU changes something.
  bool idleSinceCheck = false;

  detail::WorldBuffers buffers;
  detail::WorldKernels kernels;
  gl::KernelProfiler profiler;
  // With sleep and without statistics each frame, what tells the next frame whether the sand
  // slept (sandLooksIdle): the counters after a frame's last substep, copied for the next frame to
  // take if the GPU has made them, never waiting (world_step.cpp).
  gl::AsyncRead idleHint{"idle hint"};

  Impl(const GpuContext& context, const WorldSettings& s);
  ~Impl();

  /// The contact law keeps contact state across substeps (HertzMindlin): slots, pair counts,
  /// torques and the sorted spins exist.
  bool keepsHistory() const { return settings.contactLaw == ContactLaw::HertzMindlin; }
  /// It keeps a rolling spring per contact slot too (Material::rollingFriction, which only
  /// HertzMindlin takes).
  bool keepsRollingHistory() const {
    return keepsHistory() && settings.material.rollingFriction > 0.0f;
  }
  /// Substeps between sorts of the granules by place (WorldSettings::sortInterval, derived);
  /// 0: never.
  std::uint32_t sortInterval() const { return granuleSortInterval(settings); }
  bool sortsGranules() const { return sortInterval() > 0; }
  /// The contacts pass leaves the particles near a collider to contacts_colliders (without sleep;
  /// with it contacts keeps the collider code): a collider changed needs a list build then.
  bool collidersInOwnPass() const { return !sleep.enabled; }
  /// One past the last particle of body slot `body`.
  std::uint32_t particleEnd(std::uint32_t body) const { return particleEnds[body]; }

  // Bodies (world_body_slots.cpp)
  std::uint32_t addBodies(const ParticleTemplate& shape, const std::vector<BodyDesc>& descs,
                          bool granule);
  /// Throws CapacityExceeded naming the limit unless this many more bodies and particles fit.
  void requireRoom(std::uint64_t bodies, std::uint64_t particles) const;
  /// The calm count of a body the CPU places (WorldSettings::sleep; 0 without it): only a
  /// kinematic one slower than the thresholds counts as calm.
  std::uint32_t placedCalm(const BodyDesc& desc) const;
  void uploadBodyStates(std::uint32_t first, const std::vector<BodyDesc>& descs,
                        const ParticleTemplate& shape);
  /// Throws InvalidArgument when a granule meeting a sampled surface (ParticleTemplate::
  /// surfaceSpacing) at maxSpeed would get between its samples (HertzMindlin;
  /// surfacePassOverlap).
  void requireImpenetrableSurface(const ParticleTemplate& shape) const;
  /// Throws InvalidId naming `id` unless it is a body of this World.
  void requireBody(BodyId id) const;
  /// Sets body slot `body`'s pose and velocities (its motion as added); its particles follow
  /// before the next contacts. Safe between the substeps of a step.
  void placeBody(std::uint32_t body, const BodyDesc& desc);
  /// Places every body whose move covers the substep count now (world_moves.cpp); nothing when
  /// no move does.
  void followMoves();
  /// The id of body slot `slot` (< bodyCount), with the slot's generation.
  BodyId bodyId(std::uint32_t slot) const;
  /// The particles of the bodies from slot `firstBody` on, just added from the CPU, are checked
  /// for deep initial overlaps at the next step.
  void checkOverlapsFrom(std::uint32_t firstBody);

  // The order of the bodies in their slots (world_order.cpp)
  /// The slot of body id `id` (< bodyCount) and the id of the body in slot `slot`; the first call
  /// after a sort that needs a dynamic body's slot reads the ids back (a sync point), which only a
  /// World that sorts ever needs.
  std::uint32_t slotOf(std::uint32_t id) const;
  std::uint32_t idOf(std::uint32_t slot) const;
  /// The ids of bodies [first, end), just added in the slots of the same indices.
  void addIds(std::uint32_t first, std::uint32_t end);
  /// Puts `ids` (the id of each slot; empty: each its own) in the GPU's and the CPU's tables.
  void setIds(std::span<const std::uint32_t> ids);
  /// Every slot's id, or none while each slot holds the body of its own index. Sync point after a
  /// sort.
  std::span<const std::uint32_t> slotIds() const;
  /// The substep count calls for a sort of the granules by place.
  bool granuleSortDue() const;
  /// prepareContacts with a sort of the granules by place: every list built, the granules sorted
  /// in the order of that build's grid (every particle in use is in it), the lists built again.
  void prepareContactsAndSort();
  /// prepareActive with a sort of the granules by place: every list built, the granules the
  /// substep computes sorted among their own slots in the order of that build's moving grid, the
  /// lists built again; nothing more when the substep computes nothing (the GPU decides).
  void prepareActiveAndSort();
  void sortGranules();
  /// A pass of the sort over `over`: with sleep from its indirect command (collect_active.comp
  /// wrote it, zero groups when there is no sort), otherwise `threads` in workgroups of
  /// `groupSize`.
  void dispatchSortPass(GLuint program, const char* name, detail::SortPass over,
                        std::uint32_t threads, std::uint32_t groupSize);
  /// One buffer's words moved to their new slots: `particles` says whether an item is a particle
  /// or a body; each item has `stride` words, of which [first, first + words) move.
  void moveWords(detail::Binding buffer, bool particles, std::uint32_t stride, std::uint32_t first,
                 std::uint32_t words);

  // Colliders (world_colliders.cpp)
  // Wakes the sleeping granules whose centres lie in `box` (wake_region.comp); nothing without
  // sleep.
  void wakeBox(const detail::Bounds& box);
  ColliderId putCollider(std::optional<std::uint32_t> slot, const detail::GpuCollider& collider,
                         const ColliderShape& shape);
  /// Throws InvalidArgument for a thin wall (cylinder, funnel) moving so fast that a granule's
  /// particle meeting it would pass through (HertzMindlin; the paper's law caps the overlap).
  void requireUntunnelledWall(const ColliderShape& shape) const;

  /// Particles [first, end) take their state from their bodies before the next contacts.
  void markParticlesDirty(std::uint32_t first, std::uint32_t end);
  void markBodiesChanged(std::uint32_t first, std::uint32_t end);
  /// The contacts of particles [first, end) deeper than `minOverlap` (m), each pair once or, with
  /// `bothSides`, from each listed particle's side (contacts.comp compiled for CONTACT_LIST);
  /// sorted. Sync point.
  std::vector<ContactRecord> listContacts(std::uint32_t first, std::uint32_t end, float minOverlap,
                                          bool bothSides);
  /// The check of checkOverlapsFrom, then forgotten; prints a warning when something overlaps.
  InitialOverlaps checkInitialOverlaps();

  // GPU work (world_kernels.cpp)
  void uploadParams();
  /// The table for particleCount, from the start of a substep on (the grid of the last build,
  /// which spawn checks read, keeps the table it was built with); a new table asks for a build.
  void fitTable();
  /// What the contacts of a substep need first: the particles the CPU changed, and the neighbour
  /// lists, built on the GPU's decision (list_check.comp) with indirect dispatches.
  void prepareContacts();
  /// With sleep, what a substep does before its contacts: the bodies and particles it computes
  /// listed (collect_active), and the list build if one is due.
  void prepareActive();
  /// The contacts of the particles the contacts pass left to the grid search.
  void searchContacts();
  /// Its parts: the particles the CPU changed (and a build request when it changed bodies), and
  /// the build's passes, which run with zero groups when the decision found no build due.
  void prepareBodies();
  /// The particles of bodies the CPU set since the last substep, from their bodies (the same pass
  /// the next substep would run first, so running it earlier changes no bit); `name` as dispatch.
  void writeDirtyParticles(const char* name);
  void buildLists();
  void runSubstep();
  /// The substep count and the simulated time, one substep on (every substep ends with it, run
  /// or skipped as idle).
  void advanceClock();
  /// Whether the last substep computed nothing (computedNothing), from the counters it
  /// downloads. Sync point.
  bool lastSubstepComputedNothing();
  /// With sleep and without statistics each frame: the last frame's idleHint, if it is ready,
  /// sets sandLooksIdle; after a frame that ran substeps and was not found idle, the next hint.
  void takeIdleHint();
  void startIdleHint(std::uint64_t substepsRun);
  /// After a substep that computed nothing (lastSubstepComputedNothing): the statistics and the
  /// peak overlaps are as current and as clear as they were before it, and the substeps after it
  /// idle until something changes.
  void substepChangedNothing(bool statsWereCurrent, bool peaksWereClear);
  /// `name` nullptr: not timed by the profiler (a pass outside the substeps).
  void dispatch(GLuint program, const char* name, std::uint32_t threads, std::uint32_t groupSize);
  /// A pass whose group counts the GPU wrote into the counters at `commandOffset` (bytes): the
  /// list build's passes (listDispatchOffset) and, with sleep, those over the active lists
  /// (activeDispatchOffset).
  void dispatchIndirect(GLuint program, const char* name, std::uint32_t commandOffset);
  void emit(double dt, StepReport* report);
  /// spawn_check.comp over the `count` granules just added from body slot `firstBody`.
  void checkSpawnPlaces(std::uint32_t firstBody, std::uint32_t count);
  /// Something the statistics read may have changed, or the next substep may compute something:
  /// the next readStats reduces, the next step resets the peak overlaps and runs its first
  /// substep.
  void stateChanged() { statsCurrent = peaksClear = idleSinceCheck = false; }
  /// Whether a substep that computes nothing can stand for the ones after it in a frame: sleep
  /// is on and no CPU work waits for a later substep (an emitter, a kinematic move).
  bool idleSubstepsRepeat() const;
  /// Whether the counters (kCounterCount words) show that the last substep listed no body and no
  /// particle to compute (collect_active.comp).
  static bool computedNothing(std::span<const std::uint32_t> counters);

  // Statistics (world_stats.cpp)
  /// The statistics: those of the last reduce while they are current, else a new reduce.
  WorldStats readStats();
  /// stats_reduce.comp over every particle and body, and the counters. Sync point.
  WorldStats reduceStats();
  /// The fields of `s` that the CPU keeps or the counters hold.
  void fillKeptFields(WorldStats& s) const;
  /// The peak overlap of every particle restarts at zero (reset_peak_overlap.comp; nothing to do
  /// while peaksClear).
  void resetPeakOverlap();
};

}  // namespace sandphys
