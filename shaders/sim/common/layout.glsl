// Layout shared by every simulation kernel: constants, structs and the uniform block, whose C++
// twin is sandphys/src/core/gpu_layout.h (a test checks that the two agree). The storage buffers
// are declared once, in sandphys/src/core/gpu_buffers.def, from which the shader loader generates
// buffers.glsl: MACRO(access) for each buffer and MACRO_TEXTURE for its read-only buffer-texture
// view, if it has one. A kernel declares only the buffers it touches, with the access it needs,
// through these macros, and reads through a view only what earlier dispatches wrote, never a
// buffer it writes itself.
#include "buffers.glsl"

#define WORKGROUP_SIZE 64

// Body flags (bodyInfo.z).
#define BODY_ALIVE 1u
#define BODY_GRANULE 2u
// Every body that is not a granule: summed and moved by integrate_large_bodies.comp.
#define BODY_LARGE 8u
#define BODY_MOTION_SHIFT 4u
#define BODY_MOTION_MASK 0x30u
// From this bit on, a large body's entry in largeBodies and largeBodyForces.
#define BODY_ENTRY_SHIFT 8u
#define MOTION_DYNAMIC 0u
#define MOTION_KINEMATIC 1u
#define MOTION_STATIC 2u

#define INVALID_CELL 0xffffffffu
// bodyGridBuild of a body that died (common/grid.glsl).
#define GRID_BUILD_DEAD 0xffffffffu

// Neighbour-list entries per particle.
#define NEIGHBOUR_LIST_CAPACITY 16
// listOrigin.w of a particle whose body was dead at the last build.
#define LIST_DEAD 0xffffffffu
// Set in listNear.w beside the marked entries when list_near.comp found a collider near the
// particle (common/neighbour_list.glsl).
#define LIST_NEAR_COLLIDER 0x80000000u
// Buckets per workgroup of the block scan.
#define SCAN_BLOCK 1024u

struct Collider {
  vec4 a;         // meaning depends on the type (see colliders.glsl)
  vec4 b;
  vec4 c;
  vec4 material;  // x: type, y: friction, z: damping factor c(e), w: ColliderId (uint bits)
  // The surface's velocity at x is velocity.xyz + cross(spin.xyz, x) (ColliderMotion, with the
  // reference point folded into velocity on the CPU).
  vec4 velocity;
  vec4 spin;
};

struct SinkBox {
  vec4 lo;
  vec4 hi;
};

// counters[] (COUNTERS).
#define COUNTER_KILLED 0
// Emitted granules not born because their place was taken (spawn_check.comp).
#define COUNTER_SPAWN_TAKEN 1
// Non-zero when the neighbour lists must be built before the next contacts (list_check.comp reads
// and clears it): LIST_REQUEST_ALL when the CPU asked (bodies added or restored, a new table),
// LIST_REQUEST_MOVED when a particle moved more than half the skin since the last build or a
// granule died. Under SLEEPING the second builds the lists of the active particles only.
#define COUNTER_LIST_REQUESTED 2
#define LIST_REQUEST_ALL 1u
#define LIST_REQUEST_MOVED 2u
// Neighbour list builds so far.
#define COUNTER_LIST_BUILDS 3
// Particles that had more partners than NEIGHBOUR_LIST_CAPACITY at a build (total).
#define COUNTER_LIST_OVERFLOWS 4
// SLEEPING: the entries collect_active.comp has put in the active lists so far this substep, and
// its workgroups done (the last one turns them into the commands below and clears them).
#define COUNTER_ACTIVE_BODIES 5
#define COUNTER_ACTIVE_PARTICLES 6
#define COUNTER_ACTIVE_GROUPS_DONE 7
// SLEEPING: non-zero when the build due builds every particle's list, zero when only the active
// particles' (list_build.comp).
#define COUNTER_LIST_ALL 8
// SLEEPING, the two grids (common/grid.glsl): the build that last built the still grid, and how
// many builds did; the particles of the last build's moving grid from the active list and from
// the recent sleepers; and the recent sleepers' particles collect_active.comp has listed so far.
#define COUNTER_STILL_BUILD 9
#define COUNTER_STILL_BUILDS 10
#define COUNTER_GRID_ACTIVE 11
#define COUNTER_GRID_RECENT 12
#define COUNTER_RECENT_PARTICLES 13
// Non-zero in the first substep after the CPU changed the bodies (added, restored): a restored
// state's counts need not be those of its slots (a snapshot made by hand), so
// integrate_bodies.comp takes every granule's pair counts (common/contact_pairs.glsl), as before
// the change, not only those whose slots changed. Only the CPU writes it.
#define COUNTER_RECOUNT_PAIRS 14
// Six words: the extent of the cells the grid was last fitted to (grid_extent.comp,
// common/grid_fit.glsl), zero before any.
#define COUNTER_GRID_EXTENT 15
// Without sleep: the particles the last list build listed for contacts_colliders and for
// contacts_search (list_build.comp), to which each substep's lists go back before the contacts
// passes add the particles they leave to those passes in the substep (clearRunningCommands in
// common/list_decision.glsl).
#define COUNTER_COLLIDERS_LISTED 21
#define COUNTER_SEARCH_LISTED 22
// Without sleep: non-zero when the near part of the lists is marked again before the next
// contacts (a particle moved more than half the near skin since it was last marked;
// list_check.comp reads and clears it).
#define COUNTER_NEAR_REQUESTED 23
// Without sleep: markings of the lists' near part so far (list_near.comp).
#define COUNTER_NEAR_MARKINGS 24
// SLEEPING: the large bodies collect_active.comp has listed so far this substep.
#define COUNTER_ACTIVE_LARGE 25
// The granules the last sort by place found in the grid's order (order_sources.comp).
#define COUNTER_ORDER_SEQUENCE 26
// SLEEPING: SORT_REQUESTED when the CPU sorts the granules by place in this substep;
// collect_active.comp reads and clears it and writes the sort's commands (COUNTER_SORT_DISPATCH).
#define COUNTER_GRANULE_SORT 27
#define SORT_REQUESTED 1u
// From this uint on: the indirect dispatch commands of the list build, one per pass below (4
// uints each: groups x, y, z and padding), zero groups when no build is due.
#define COUNTER_LIST_DISPATCH 28
#define PASS_GRID_EXTENT 0u
#define PASS_GRID_COUNT 1u
#define PASS_SCAN_BLOCKS 2u
#define PASS_SCAN_BLOCK_SUMS 3u
#define PASS_SCAN_ADD 4u
#define PASS_GRID_SCATTER 5u
#define PASS_GRID_SORT 6u
#define PASS_LIST_BUILD 7u
// Not a pass of the build: the marking of the lists' near part (list_near.comp), after a build
// or when a particle moved half the near skin.
#define PASS_LIST_NEAR 8u
#define LIST_BUILD_PASSES 9
// After those, the indirect commands of the passes over lists: under SLEEPING the contacts and
// integrate_bodies passes over the active lists (ACTIVE_PARTICLES, ACTIVE_BODIES), the count_pairs
// pass over the granules due (PAIRS_DUE), the contacts passes over the particles that search the
// grid (SEARCH_DUE) and over those near a collider (COLLIDERS_DUE); the fourth uint of each is the
// list's length. Under SLEEPING the length of the active large bodies (ACTIVE_LARGE_BODIES) follows
// them, with no command: integrate_large_bodies is dispatched over every large body, and its
// workgroups beyond the length return (an indirect dispatch costs llvmpipe a wait, more than a
// few empty workgroups).
#define COUNTER_ACTIVE_DISPATCH (COUNTER_LIST_DISPATCH + 4 * LIST_BUILD_PASSES)
#define ACTIVE_PASS_CONTACTS 0u
#define ACTIVE_PASS_BODIES 1u
#define ACTIVE_PASS_PAIRS 2u
#define ACTIVE_PASS_SEARCH 3u
#define ACTIVE_PASS_COLLIDERS 4u
#define ACTIVE_PASS_LARGE 5u
#define ACTIVE_PASSES 6
// SLEEPING: after those, the indirect commands of the sort of the granules by place, one per
// size its passes run over (World::Impl::sortGranules): full in a substep that sorts and computes
// something, zero in one that computes nothing, which sorts nothing (as a frame that skips it,
// StepReport::idleSubsteps, does not), both written by collect_active.comp.
#define COUNTER_SORT_DISPATCH (COUNTER_ACTIVE_DISPATCH + 4 * ACTIVE_PASSES)
#define SORT_OVER_PARTICLES 0u
#define SORT_OVER_BODIES 1u
#define SORT_OVER_SCAN_BLOCKS 2u
#define SORT_OVER_BLOCK_SUMS 3u
#define SORT_PASSES 4
// The length of the active list a pass runs over (the includer declares COUNTERS).
#define activeListLength(pass) counters[COUNTER_ACTIVE_DISPATCH + 4u * (pass) + 3u]

struct StatsPartial {
  uvec4 counts;  // x: particle-particle contact ends; y: collider contacts; z: penetration guards; w: velocity guards
  vec4 sums;     // x: translational KE (J); y: rotational KE (J); z: max overlap (m); w: alive granules
  uvec4 sleep;   // x: sleeping granules (SLEEPING); y, z, w: unused
};

// Contact slots (CONTACT_SLOTS_0...): per particle, in CONTACT_SLOT_GROUPS buffers.
#define CONTACT_SLOTS 12
#define CONTACT_SLOTS_PER_GROUP 4
#define CONTACT_SLOT_GROUPS 3
// Vec4s per record of the contact list (C++: GpuContactRecord).
#define CONTACT_RECORD 7

// Sleep (SLEEPING, docs/architecture.md "sleep"). A body's calm count is the number of substeps its
// speeds have been below the thresholds, but at most params.sleepNeighbourLead more than the
// smallest count among the bodies it touches: so a body reaches params.sleepSubsteps, and sleeps,
// only when nothing within kSleepContacts contacts of it moves, and a calm touching group falls
// asleep together. Dynamic bodies sleep, and so does a kinematic body set exactly at rest (sleep
// stops a body dead, which must not change a kinematic body's motion); the count of every other
// movable body stops at params.sleepSubsteps - 1 (calmLimit in rigid_motion.glsl). The contacts
// pass leaves in particleForce.w the smallest count among the particle's partners
// (CALM_UNBOUNDED: none), 0 when a moving collider touches it or, asleep, when its contacts are
// not those it fell asleep with. An awake particle marks the sleeping bodies it touches by setting
// their count (not their particles' copies) to calmTouched(): they are computed in the next
// substep (collect_active.comp takes the mark back to params.sleepSubsteps).
#define CALM_UNBOUNDED 0xffffffffu
#define calmTouched() (params.sleepSubsteps + 1u)
// Bodies per thread of collect_active.comp, a chunk of quietChunks each (C++: kCollectChunk).
#define COLLECT_CHUNK 32u

// Constant for the whole step; set by World when settings or counts change (C++ twin: SimParams
// in gpu_layout.h). std140 with one vec3, first, and 4-byte members after it: nothing is padded.
layout(std140, binding = 0) uniform SimParams {
  vec3 gravity;                // m/s^2
  float dt;                    // the substep (s)
  float particleRadius;        // m
  float particleDiameter;      // d (m)
  float inverseCellSize;       // 1 / (d + skin) (1/m): the hash grid's cells
  float maxOverlap;            // PAPER_LAW's penetration guard (m)
  float grainStiffness;        // k_n grain-grain
  float grainDamping;          // c(e) grain-grain
  float friction;              // grain-grain
  float tangentialDamping;     // PAPER_LAW
  float wallStiffness;         // k_n grain-wall
  float maxSpeed;              // velocity guard (m/s)
  uint particleCount;
  uint bodyCount;
  uint hashMask;               // hashSize - 1
  uint sinkCount;
  uint hashSize;               // buckets, a power of two
  uint hashMultiplierY;        // spatial_hash.glsl
  uint hashMultiplierZ;
  // Colliders are sorted by type: the planes end at planesEnd, boxes at boxesEnd, walls of
  // revolution at revolutionsEnd.
  uint planesEnd;
  uint boxesEnd;
  uint revolutionsEnd;
  float grainShearStiffness;   // k_t0 grain-grain (N/m^3/2; k_t = k_t0 sqrt(xi))
  float wallShearStiffness;    // k_t0 grain-wall
  float listReachSquared;      // (d + skin)^2 (m^2): a pair closer than this is listed
  // A hair under (skin / 2)^2 (m^2): a particle that moved this far asks for a build.
  float listMoveSquared;
  float nearReachSquared;      // (d + near skin)^2 (m^2): a listed pair closer than this is near
  // A hair under (near skin / 2)^2 (m^2): a particle that moved this far asks for a marking.
  float nearMoveSquared;
  uint listStride;             // of a neighbour-list entry: the particles in use
  float sleepLinearSpeed;      // SLEEPING: speed thresholds (m/s, rad/s)
  float sleepAngularSpeed;
  float wakeAcceleration;      // SLEEPING: m/s^2
  uint sleepSubsteps;          // SLEEPING: SleepModel::substeps, calm substeps before sleep
  uint sleepNeighbourLead;     // SLEEPING: SleepModel::neighbourLead
  uint oneGrid;                // SLEEPING: 1 sorts every particle into one grid at every build (a test's oracle)
  float rollingFriction;       // ROLLING_FRICTION: mu_r (contact_law.glsl, rollingTorque)
} params;

// Linear thread index of a dispatch that World may fold into two dimensions. A macro, because
// gl_WorkGroupSize exists only after the kernel's own local_size declaration.
#define threadIndex() (gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x)
