// Buffer layout shared by every simulation kernel; the C++ twin is sandphys/src/core/gpu_layout.h
// (a test checks that the two agree). One std430 buffer per attribute, packed in vec4/uvec4: a
// vec3 would be padded to 16 bytes anyway. A kernel declares only the buffers it touches, with
// the access it needs, through these macros.

#define WORKGROUP_SIZE 64

// Body flags (bodyInfo.z).
#define BODY_ALIVE 1u
#define BODY_GRANULE 2u
// Every body that is not a granule: summed and moved by integrate_large_bodies.comp.
#define BODY_LARGE 8u
#define BODY_MOTION_SHIFT 4u
#define BODY_MOTION_MASK 0x30u
#define MOTION_DYNAMIC 0u
#define MOTION_KINEMATIC 1u
#define MOTION_STATIC 2u

#define INVALID_CELL 0xffffffffu

// xyz: centre of mass (m); w: inverse mass (1/kg), 0 for kinematic and static bodies.
#define BODY_POSITION(access) layout(std430, binding = 0) access buffer BodyPositionBuffer { vec4 bodyPosition[]; };
// Unit quaternion (x, y, z, w) from the body's principal frame to the world.
#define BODY_ORIENTATION(access) layout(std430, binding = 1) access buffer BodyOrientationBuffer { vec4 bodyOrientation[]; };
// xyz: linear velocity (m/s); w: calm count (uint bits; see "Sleep" below, 0 without SLEEPING).
#define BODY_VELOCITY(access) layout(std430, binding = 2) access buffer BodyVelocityBuffer { vec4 bodyVelocity[]; };
// xyz: angular velocity (rad/s, world frame); w: bounding radius (m).
#define BODY_ANGULAR_VELOCITY(access) layout(std430, binding = 3) access buffer BodyAngularVelocityBuffer { vec4 bodyAngularVelocity[]; };
// xyz: principal moments of inertia (kg m^2); w: mass (kg).
#define BODY_INERTIA(access) layout(std430, binding = 4) access buffer BodyInertiaBuffer { vec4 bodyInertia[]; };
// x: first particle, y: particle count, z: flags, w: velocity-guard count.
#define BODY_INFO(access) layout(std430, binding = 5) access buffer BodyInfoBuffer { uvec4 bodyInfo[]; };
// xyz: particle centre in the body's principal frame (m); w: particle inverse mass (1/kg): 0 for
// kinematic bodies, -1 for static ones (their particles need no force at all).
#define PARTICLE_LOCAL(access) layout(std430, binding = 6) access buffer ParticleLocalBuffer { vec4 particleLocal[]; };
// Owning body of each particle.
#define PARTICLE_BODY(access) layout(std430, binding = 7) access buffer ParticleBodyBuffer { uint particleBody[]; };
// The particle state a substep starts from, written where its body moved (the integration
// passes; bodies_to_particles.comp after the CPU set bodies). xyz: world position (m); w: owning
// body (uint bits).
#define PARTICLE_POSITION(access) layout(std430, binding = 8) access buffer ParticlePositionBuffer { vec4 particlePosition[]; };
// xyz: world velocity (m/s), eq. 8; w: particle inverse mass as in particleLocal (-1: static).
#define PARTICLE_VELOCITY(access) layout(std430, binding = 9) access buffer ParticleVelocityBuffer { vec4 particleVelocity[]; };
// xyz: contact + collider force of the last substep (N); w: SLEEPING: the neighbours' calm
// (uint bits; see "Sleep" below), 0 otherwise.
#define PARTICLE_FORCE(access) layout(std430, binding = 10) access buffer ParticleForceBuffer { vec4 particleForce[]; };
// x: particle-particle contacts in the last substep; y: largest overlap since the stats were read
// (float bits); z: guard count since creation (PAPER_LAW: overlaps capped; otherwise contacts that
// found no free slot); w: collider contacts in the last substep.
#define PARTICLE_STATS(access) layout(std430, binding = 11) access buffer ParticleStatsBuffer { uvec4 particleStats[]; };
// Particles per hash bucket; returns to zero after every scatter.
#define CELL_COUNT(access) layout(std430, binding = 12) access buffer CellCountBuffer { uint cellCount[]; };
// Exclusive prefix sum of cellCount; entry tableSize holds the total.
#define CELL_START(access) layout(std430, binding = 13) access buffer CellStartBuffer { uint cellStart[]; };
// Particle ids in bucket order, ascending id inside each bucket.
#define CELL_PARTICLES(access) layout(std430, binding = 14) access buffer CellParticlesBuffer { uint cellParticles[]; };
// Neighbour lists (common/neighbour_list.glsl): per particle, the ids of the particles of other
// bodies that were closer than d + skin at the last build, ascending; entry k of particle i at
// k * params.listStride (the particles in use) + i, so that the threads of a dispatch read one entry
// together. At most NEIGHBOUR_LIST_CAPACITY entries per particle.
#define NEIGHBOUR_LIST_CAPACITY 16
#define NEIGHBOUR_LIST(access) layout(std430, binding = 15) access buffer NeighbourListBuffer { uint neighbourList[]; };
// Per particle, xyz: its position at the last list build (m); w: how many partners it had then
// (uint bits; more than NEIGHBOUR_LIST_CAPACITY: the rest are found again in the grid).
// listOrigin.w of a particle whose body was dead at the last build.
#define LIST_DEAD 0xffffffffu
#define LIST_ORIGIN(access) layout(std430, binding = 16) access buffer ListOriginBuffer { vec4 listOrigin[]; };
// Hash bucket of each particle at the last list build, or INVALID_CELL for particles of dead
// bodies.
#define PARTICLE_CELL(access) layout(std430, binding = 17) access buffer ParticleCellBuffer { uint particleCell[]; };
// Per-workgroup sums of the block scan, whose workgroups take SCAN_BLOCK buckets each
// (scan_blocks.comp, scan_add.comp: 256 threads of 4).
#define SCAN_BLOCK 1024u
#define SCAN_BLOCK_SUMS(access) layout(std430, binding = 18) access buffer ScanBlockSumsBuffer { uint scanBlockSums[]; };

// Read-only views of some of the buffers above as buffer textures (same memory, no copy); the
// units are TextureUnit in gpu_layout.h. A texel fetch is the fast gather path on GPUs and on
// llvmpipe, whose SSBO loads at per-invocation offsets run lane by lane. A kernel reads through a
// view only what earlier dispatches wrote, never a buffer it writes itself.
#define NEIGHBOUR_LIST_TEXTURE layout(binding = 0) uniform usamplerBuffer neighbourListTexture;
#define LIST_ORIGIN_TEXTURE layout(binding = 1) uniform samplerBuffer listOriginTexture;
#define CELL_START_TEXTURE layout(binding = 2) uniform usamplerBuffer cellStartTexture;
#define BODY_POSITION_TEXTURE layout(binding = 3) uniform samplerBuffer bodyPositionTexture;
#define BODY_ORIENTATION_TEXTURE layout(binding = 4) uniform samplerBuffer bodyOrientationTexture;
#define BODY_VELOCITY_TEXTURE layout(binding = 5) uniform samplerBuffer bodyVelocityTexture;
#define BODY_ANGULAR_VELOCITY_TEXTURE layout(binding = 6) uniform samplerBuffer bodyAngularVelocityTexture;
#define BODY_INFO_TEXTURE layout(binding = 7) uniform usamplerBuffer bodyInfoTexture;
#define PARTICLE_LOCAL_TEXTURE layout(binding = 8) uniform samplerBuffer particleLocalTexture;
#define PARTICLE_BODY_TEXTURE layout(binding = 9) uniform usamplerBuffer particleBodyTexture;
#define PARTICLE_POSITION_TEXTURE layout(binding = 10) uniform samplerBuffer particlePositionTexture;
#define PARTICLE_VELOCITY_TEXTURE layout(binding = 11) uniform samplerBuffer particleVelocityTexture;
#define PARTICLE_FORCE_TEXTURE layout(binding = 12) uniform samplerBuffer particleForceTexture;
#define CELL_PARTICLES_TEXTURE layout(binding = 13) uniform usamplerBuffer cellParticlesTexture;
#define CELL_COUNT_TEXTURE layout(binding = 14) uniform usamplerBuffer cellCountTexture;
#define PARTICLE_TORQUE_TEXTURE layout(binding = 15) uniform samplerBuffer particleTorqueTexture;
#define PARTICLE_SPIN_TEXTURE layout(binding = 16) uniform samplerBuffer particleSpinTexture;
#define CONTACT_SLOTS_0_TEXTURE layout(binding = 17) uniform samplerBuffer contactSlots0Texture;
#define CONTACT_SLOTS_1_TEXTURE layout(binding = 18) uniform samplerBuffer contactSlots1Texture;
#define CONTACT_SLOTS_2_TEXTURE layout(binding = 19) uniform samplerBuffer contactSlots2Texture;
#define CONTACT_PAIRS_TEXTURE layout(binding = 20) uniform usamplerBuffer contactPairsTexture;

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
#define COLLIDERS(access) layout(std430, binding = 19) access buffer ColliderBuffer { Collider colliders[]; };

struct SinkBox {
  vec4 lo;
  vec4 hi;
};
#define SINKS(access) layout(std430, binding = 20) access buffer SinkBuffer { SinkBox sinks[]; };

// Integer counters updated with atomics only on rare events (never in force sums).
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
// From this uint on: the indirect dispatch commands of the list build, one per pass below (4
// uints each: groups x, y, z and padding), zero groups when no build is due.
#define COUNTER_LIST_DISPATCH 12
#define PASS_GRID_COUNT 0u
#define PASS_SCAN_BLOCKS 1u
#define PASS_SCAN_BLOCK_SUMS 2u
#define PASS_SCAN_ADD 3u
#define PASS_GRID_SCATTER 4u
#define PASS_GRID_SORT 5u
#define PASS_LIST_BUILD 6u
#define LIST_BUILD_PASSES 7
// SLEEPING: after those, the indirect commands of the contacts and integrate_bodies passes over
// the active lists (ACTIVE_PARTICLES, ACTIVE_BODIES); the fourth uint of each is the list's length.
#define COUNTER_ACTIVE_DISPATCH (COUNTER_LIST_DISPATCH + 4 * LIST_BUILD_PASSES)
#define ACTIVE_PASS_CONTACTS 0u
#define ACTIVE_PASS_BODIES 1u
// The length of the active list a pass runs over (the includer declares COUNTERS).
#define activeListLength(pass) counters[COUNTER_ACTIVE_DISPATCH + 4u * (pass) + 3u]
#define COUNTERS(access) layout(std430, binding = 21) access buffer CounterBuffer { uint counters[]; };
// Partial sums of the statistics reduction, one per workgroup (see stats_reduce.comp).
struct StatsPartial {
  uvec4 counts;  // x: particle-particle contact ends; y: collider contacts; z: penetration guards; w: velocity guards
  vec4 sums;     // x: translational KE (J); y: rotational KE (J); z: max overlap (m); w: alive granules
  uvec4 sleep;   // x: sleeping granules (SLEEPING); y, z, w: unused
};
#define STATS_PARTIALS(access) layout(std430, binding = 22) access buffer StatsPartialsBuffer { StatsPartial statsPartials[]; };
// Contact list for read-back: 5 vec4 per record (contacts.comp with CONTACT_LIST).
#define CONTACT_LIST_BUFFER(access) layout(std430, binding = 23) access buffer ContactListBuffer { uint contactListCount; uint contactListCapacity; uint pad0; uint pad1; vec4 contactList[]; };

// Body slot of each body flagged BODY_LARGE, in the order they were added.
#define LARGE_BODIES(access) layout(std430, binding = 24) access buffer LargeBodiesBuffer { uint largeBodies[]; };
// Per entry of largeBodies, two vec4: the contact force on the body (xyz, N) and its torque
// about the centre of mass (xyz, N m), each summed over the substeps since World last read them;
// the force's w counts those substeps.
#define LARGE_BODY_FORCES(access) layout(std430, binding = 25) access buffer LargeBodyForcesBuffer { vec4 largeBodyForces[]; };
// Per workgroup of state_hash.comp, the two 32-bit lanes of its bodies' hash sums.
#define STATE_HASH_PARTIALS(access) layout(std430, binding = 26) access buffer StateHashPartialsBuffer { uvec2 stateHashPartials[]; };
// xyz: torque of the last substep's contact forces about the particle's centre (N m): friction
// acting at the contact point (ContactLaw::HertzMindlin; zero under PAPER_LAW).
#define PARTICLE_TORQUE(access) layout(std430, binding = 27) access buffer ParticleTorqueBuffer { vec4 particleTorque[]; };
// Per particle (HertzMindlin), written with particlePosition: xyz: angular velocity of the
// owning body (rad/s), so that a contact reads its partner's spin in one fetch; w: the owning
// body's calm count (uint bits; CALM_UNBOUNDED for immovable bodies), 0 without SLEEPING.
#define PARTICLE_SPIN(access) layout(std430, binding = 28) access buffer ParticleSpinBuffer { vec4 particleSpin[]; };
// The contacts of ContactLaw::HertzMindlin that persist across substeps (common/contact_slots.glsl):
// CONTACT_SLOTS slots per particle, CONTACT_SLOTS_PER_GROUP of them in each of the group buffers
// (one buffer would outgrow the 128 MiB a storage block may hold). Slot k of particle i is entry
// i * CONTACT_SLOTS_PER_GROUP + k % CONTACT_SLOTS_PER_GROUP of group k / CONTACT_SLOTS_PER_GROUP.
// xyz: tangential spring displacement (m); w: partner key (uint bits, contact_slots.glsl).
#define CONTACT_SLOTS 12
#define CONTACT_SLOTS_PER_GROUP 4
#define CONTACT_SLOT_GROUPS 3
#define CONTACT_SLOTS_0(access) layout(std430, binding = 29) access buffer ContactSlots0Buffer { vec4 contactSlots0[]; };
#define CONTACT_SLOTS_1(access) layout(std430, binding = 30) access buffer ContactSlots1Buffer { vec4 contactSlots1[]; };
#define CONTACT_SLOTS_2(access) layout(std430, binding = 31) access buffer ContactSlots2Buffer { vec4 contactSlots2[]; };
// Per particle, the number of contacts between its body and the partner of each slot, one byte
// per slot (slot k in byte k % 4 of component k / 4), counted over the body's slots after the
// contacts of a substep: the n that shares the bodies' masses among their contacts; w: slots in
// use (at least that many: a particle left without contacts may keep a stale count).
#define CONTACT_PAIRS(access) layout(std430, binding = 32) access buffer ContactPairsBuffer { uvec4 contactPairs[]; };

// SLEEPING: the particles and the granules a substep computes (collect_active.comp): those of
// awake bodies and of sleeping ones something awake touched in the last substep; in blocks of a
// workgroup, ascending inside a block, the blocks in any order (no result depends on the order:
// each thread gathers for its own particle or body).
#define ACTIVE_BODIES(access) layout(std430, binding = 33) access buffer ActiveBodiesBuffer { uint activeBodies[]; };
#define ACTIVE_PARTICLES(access) layout(std430, binding = 34) access buffer ActiveParticlesBuffer { uint activeParticles[]; };
// SLEEPING: per particle, the build (COUNTER_LIST_BUILDS) its neighbour list comes from. A build
// that the motion asked for lists the active particles only; a particle whose list is older than
// the last build finds its partners in the grid instead (contacts.comp).
#define LIST_BUILT(access) layout(std430, binding = 35) access buffer ListBuiltBuffer { uint listBuilt[]; };

// Sleep (SLEEPING, docs/architecture.md "sleep"). A body's calm count is the number of substeps its
// speeds have been below the thresholds, but at most params.sleepNeighbourLead more than the
// smallest count among the bodies it touches: so a body reaches params.sleepSubsteps, and sleeps,
// only when nothing within kSleepContacts contacts of it moves, and a calm touching group falls
// asleep together. Only dynamic granules sleep; the count of every other movable body stops at
// params.sleepSubsteps - 1. The contacts pass leaves in particleForce.w the smallest count among
// the particle's partners (CALM_UNBOUNDED: none), 0 when a moving collider touches it or, asleep,
// when its contacts are not those it fell asleep with. An awake particle marks the sleeping bodies
// it touches by setting their count (not their particles' copies) to calmTouched(): they are
// computed in the next substep (collect_active.comp takes the mark back to params.sleepSubsteps).
#define CALM_UNBOUNDED 0xffffffffu
#define calmTouched() (params.sleepSubsteps + 1u)

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
  uint listStride;             // of a neighbour-list entry: the particles in use
  float sleepLinearSpeed;      // SLEEPING: speed thresholds (m/s, rad/s)
  float sleepAngularSpeed;
  float wakeAcceleration;      // SLEEPING: m/s^2
  uint sleepSubsteps;          // SLEEPING: SleepModel::substeps, calm substeps before sleep
  uint sleepNeighbourLead;     // SLEEPING: SleepModel::neighbourLead
} params;

// Linear thread index of a dispatch that World may fold into two dimensions. A macro, because
// gl_WorkGroupSize exists only after the kernel's own local_size declaration.
#define threadIndex() (gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x)
