#pragma once

// C++ twin of shaders/sim/common/layout.glsl: its constants, structs and uniform block. A test
// compiles a probe shader and checks these sizes and offsets against the driver's view of the
// GLSL declarations. The buffers themselves are declared once, in gpu_buffers.def.

#include <cstddef>
#include <cstdint>

#include "sandphys/math.h"

#include "sandphys/snapshot.h"

namespace sandphys::detail {

inline constexpr unsigned kSimParamsBinding = 0;
inline constexpr unsigned kWorkgroupSize = 64;
inline constexpr unsigned kScanBlock = 1024;      // elements per scan workgroup (256 x 4)
inline constexpr unsigned kStatsWorkgroups = 32;  // fixed: the reduction order never changes
// counters[] (layout.glsl, COUNTER_*): rare events, the neighbour lists' control and, from
// kCounterListDispatch on, the indirect commands of the list build's passes, then those of the
// passes over lists (the active lists, with sleep; the granules due for their pair counts; the
// particles left to the grid search), then with sleep those of the sort of the granules. Words
// 5-9, 13, 15-23, 25 and 26 are the GPU's alone (layout.glsl).
inline constexpr std::uint32_t kCounterKilled = 0;
inline constexpr std::uint32_t kCounterSpawnTaken = 1;
inline constexpr std::uint32_t kCounterListRequested = 2;
inline constexpr std::uint32_t kCounterListBuilds = 3;
inline constexpr std::uint32_t kCounterListOverflows = 4;
/// Sleep's two grids: builds of the still grid, and the last moving grid's particles from the
/// active list and from the sleepers that moved since the still grid was built.
inline constexpr std::uint32_t kCounterStillBuilds = 10;
inline constexpr std::uint32_t kCounterGridActive = 11;
inline constexpr std::uint32_t kCounterGridRecent = 12;
/// Non-zero while the CPU asks integrate_bodies.comp to take every granule's pair counts.
inline constexpr std::uint32_t kCounterRecountPairs = 14;
/// Markings of the lists' near part (list_near.comp), without sleep.
inline constexpr std::uint32_t kCounterNearMarkings = 24;
inline constexpr std::uint32_t kCounterListDispatch = 28;
/// COUNTER_LIST_REQUESTED values (layout.glsl): the CPU asks for every list.
inline constexpr std::uint32_t kListRequestAll = 1;
/// The passes of a list build, each dispatched from its own indirect command (list_check.comp).
enum ListBuildPass : std::uint32_t {
  kPassGridExtent,
  kPassGridCount,
  kPassScanBlocks,
  kPassScanBlockSums,
  kPassScanAdd,
  kPassGridScatter,
  kPassGridSort,
  kPassListBuild,
  kPassListNear,  // not of the build: the lists' near part marked again (list_near.comp)
  kListBuildPasses,
};
inline constexpr std::uint32_t kCounterActiveDispatch = kCounterListDispatch + 4 * kListBuildPasses;
/// The passes over lists, each from its own indirect command: SLEEPING's over the active lists
/// (collect_active.comp writes them), count_pairs.comp's over the granules whose pair counts are
/// due (integrate_bodies.comp writes it), and contacts.comp's over the particles that search the
/// grid and over those near a collider (list_build.comp writes both at a build; under SLEEPING
/// the contacts pass writes the search's).
enum ActivePass : std::uint32_t {
  kActivePassContacts,
  kActivePassBodies,
  kActivePassPairs,
  kActivePassSearch,
  kActivePassColliders,
  kActivePassLarge,  // SLEEPING: the active large bodies' length only (layout.glsl)
  kActivePasses,
};
/// SLEEPING: set to kSortRequested in a substep that sorts the granules by place;
/// collect_active.comp turns it into the sort's indirect commands (layout.glsl,
/// COUNTER_GRANULE_SORT).
inline constexpr std::uint32_t kCounterGranuleSort = 27;
inline constexpr std::uint32_t kSortRequested = 1;
inline constexpr std::uint32_t kCounterSortDispatch = kCounterActiveDispatch + 4 * kActivePasses;
/// What the sort's passes run over, each size from its own indirect command under SLEEPING.
enum SortPass : std::uint32_t {
  kSortOverParticles,
  kSortOverBodies,
  kSortOverScanBlocks,
  kSortOverBlockSums,
  kSortPasses,
};
inline constexpr std::uint32_t kCounterCount = kCounterSortDispatch + 4 * kSortPasses;
/// Byte offset of a pass's indirect command in the counters buffer.
inline constexpr std::uint32_t listDispatchOffset(ListBuildPass pass) {
  return 4 * (kCounterListDispatch + 4 * pass);
}
/// Bodies per thread of collect_active.comp, a chunk of QuietChunks each (COLLECT_CHUNK in
/// layout.glsl).
inline constexpr std::uint32_t kCollectChunk = 32;
/// Byte offset of an active pass's indirect command in the counters buffer.
inline constexpr std::uint32_t activeDispatchOffset(ActivePass pass) {
  return 4 * (kCounterActiveDispatch + 4 * pass);
}
/// Byte offset of a sort pass's indirect command in the counters buffer (SLEEPING).
inline constexpr std::uint32_t sortDispatchOffset(SortPass pass) {
  return 4 * (kCounterSortDispatch + 4 * pass);
}
/// Neighbour-list entries per particle (layout.glsl, NEIGHBOUR_LIST_CAPACITY).
inline constexpr std::uint32_t kNeighbourListCapacity = 16;

// bodyInfo.z flags
inline constexpr std::uint32_t kBodyAlive = 1u;
inline constexpr std::uint32_t kBodyGranule = 2u;
inline constexpr std::uint32_t kBodyLarge = 8u;  // not a granule: integrate_large_bodies.comp
inline constexpr std::uint32_t kBodyMotionShift = 4u;
/// From this bit of bodyInfo.z on, a large body's entry in the LargeBodies buffer.
inline constexpr std::uint32_t kBodyEntryShift = 8u;
/// Bodies that are not granules (and not static), each summed by a workgroup; the fixed size of
/// the two buffers that list them and hold their force sums.
inline constexpr std::uint32_t kMaxLargeBodies = 4096;
static_assert(std::uint64_t(kMaxLargeBodies) << kBodyEntryShift <= 1ull << 32,
              "a large body's entry must fit in bodyInfo.z");

struct alignas(16) GpuVec4 {
  float x, y, z, w;
};
/// A vector and the value packed into its w.
inline GpuVec4 toGpu(Vec3 v, float w) {
  return {v.x, v.y, v.z, w};
}
struct alignas(16) GpuUVec4 {
  std::uint32_t x, y, z, w;
};

enum ColliderType : std::uint32_t {
  kColliderPlane = 1,
  kColliderBox = 2,
  kColliderRevolution = 3,  // cylinder wall and funnel: a segment swept around the y axis
};

/// Contact slots of ContactLaw::HertzMindlin (gpu_buffers.def, contact_slots.glsl): per particle,
/// kContactSlots slots of one vec4 (spring xyz, partner key), kContactSlotsPerGroup of them in
/// each of kContactSlotGroups buffers.
inline constexpr std::uint32_t kContactSlotsPerGroup = 4;
/// The bit of a slot's partner key that marks a collider contact (SLOT_COLLIDER in
/// contact_slots.glsl; 0 is a free slot, any other key a partner particle).
inline constexpr std::uint32_t kSlotCollider = 0x80000000u;
inline constexpr std::uint32_t kContactSlotGroups = 3;
static_assert(kContactSlotsPerGroup * kContactSlotGroups == kContactSlots);

/// struct Collider in layout.glsl.
struct GpuCollider {
  GpuVec4 a;
  GpuVec4 b;
  GpuVec4 c;
  GpuVec4 material;  // x: type, y: friction, z: damping factor c(e), w: ColliderId (uint bits)
  GpuVec4 velocity;  // surface velocity at x: velocity + spin × x
  GpuVec4 spin;
};

/// struct SinkBox in layout.glsl.
struct GpuSink {
  GpuVec4 lo;
  GpuVec4 hi;
};

/// One record of the contact list (contacts.comp with CONTACT_LIST): CONTACT_RECORD (7) vec4.
struct GpuContactRecord {
  std::uint32_t particleA, particleB, bodyA, bodyB;
  float px, py, pz, overlap;
  float nx, ny, nz, normalForce;
  float tx, ty, tz;
  std::uint32_t collider;
  float sx, sy, sz, unused;
  float rollingTorqueX, rollingTorqueY, rollingTorqueZ, unused1;
  float rollingSpringX, rollingSpringY, rollingSpringZ, unused2;
};

/// Partial sums written by one workgroup of stats_reduce.comp.
struct GpuStatsPartial {
  GpuUVec4 counts;  // x: particle-particle contact ends, y: collider contacts,
                    // z: penetration-guard count, w: velocity-guard count
  GpuVec4 sums;     // x: translational KE, y: rotational KE, z: max overlap, w: alive granules
  GpuUVec4 sleep;   // x: sleeping granules; y, z, w: unused
};

/// uniform SimParams in layout.glsl (std140), member for member; their meaning is written there.
struct alignas(16) SimParams {
  Vec3 gravity;
  float dt;
  float particleRadius;
  float particleDiameter;
  float inverseCellSize;
  float maxOverlap;
  float grainStiffness;
  float grainDamping;
  float friction;
  float tangentialDamping;
  float wallStiffness;
  float maxSpeed;
  std::uint32_t particleCount;
  std::uint32_t bodyCount;
  std::uint32_t hashMask;
  std::uint32_t sinkCount;
  std::uint32_t hashSize;
  std::uint32_t hashMultiplierY;
  std::uint32_t hashMultiplierZ;
  std::uint32_t planesEnd;
  std::uint32_t boxesEnd;
  std::uint32_t revolutionsEnd;
  float grainShearStiffness;
  float wallShearStiffness;
  float listReachSquared;
  float listMoveSquared;
  float nearReachSquared;
  float nearMoveSquared;
  std::uint32_t listStride;
  float sleepLinearSpeed;
  float sleepAngularSpeed;
  float wakeAcceleration;
  std::uint32_t sleepSubsteps;
  std::uint32_t sleepNeighbourLead;
  std::uint32_t oneGrid;
  float rollingFriction;
};

static_assert(sizeof(GpuCollider) == 96);
static_assert(sizeof(GpuSink) == 32);
static_assert(sizeof(GpuContactRecord) == 112);
static_assert(sizeof(GpuStatsPartial) == 48);
static_assert(sizeof(Vec3) == 12);  // std140 packs dt right after gravity
static_assert(sizeof(SimParams) == 160);

}  // namespace sandphys::detail
