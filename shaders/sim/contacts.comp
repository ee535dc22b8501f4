#version 450
// Pass 3. Contacts: one thread per particle evaluates its contacts with the partners of its
// neighbour list (common/neighbour_list.glsl: ascending partner id, built when some particle has
// moved more than half the skin) and with the implicit colliders, and writes its total force
// (and, under ContactLaw::HertzMindlin, the torque about its centre and its contact slots).
// Gather, not scatter: no float atomics, and the partners are summed in id order whenever the
// lists were built, so the sum is bit-identical run to run and whatever the skin.
//
// The loop over the list only marks the entries in contact (closer than a diameter), a bit each;
// the law is then evaluated for the marked entries in order. In SIMD lanes whose lists differ,
// the law's arithmetic then runs once per contact rather than once per candidate any lane has in
// contact, and no array is indexed by a count that differs between lanes. Without sleep the loop
// tests only the entries marked near (SCANS_NEAR); the search's pass tests them all.
//
// The law is chosen when the kernel is compiled: PAPER_LAW selects the paper's (eq. 9, 10;
// contactForce in common/contact_law.glsl), otherwise Hertz-Mindlin with history (hertzMindlin,
// and common/contact_slots.glsl). Compiled a second time with CONTACT_LIST defined for
// World::readContacts: the same contacts, the ones the next substep applies, are appended to a
// list (each particle pair once, from the side that keeps its history) and nothing is written.
//
// A particle with more partners than its list holds, or under SLEEPING one whose list the last
// build passed over, finds its partners in the grid. The pass leaves such a particle to a pass of
// its own, this kernel compiled with SEARCHING over the particles listed in searchDue: a search
// that one lane of a batch runs would hold up the others, and its code stays out of the pass that
// every particle runs (docs/architecture.md, "Why each pass is its own"). So does the collider
// code: a particle that the last marking of its list's near part found within half the near skin
// of a collider (LIST_NEAR_COLLIDER) is left to this kernel compiled with COLLIDERS_PASS over the
// particles listed in collidersDue; the others touch no collider until the next marking. Without
// sleep list_build.comp and list_near.comp list them; under SLEEPING this pass lists those it
// leaves to the search.
//
// Under SLEEPING (layout.glsl, "Sleep") it runs over the particles collect_active.comp listed,
// and each also finds the smallest calm count among its partners (and, awake, marks the sleeping
// ones it touches). A sleeping particle first only finds what it touches: when every partner
// sleeps or is immovable, no collider it touches moves and its contacts are those it fell asleep
// with, it writes that count and nothing else (its history stays as it was); otherwise it
// computes its contacts as an awake particle does.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"
#include "common/contact_law.glsl"
#include "common/colliders.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

// Collider surfaces found before their contacts are evaluated (see main).
#define COLLIDER_BATCH 4
// No partner found (nextPartnerAfter).
#define NO_PARTNER 0xffffffffu
// The compilations that search the grid themselves: the pass over the deferred particles and
// World::readContacts'.
#if defined(SEARCHING) || defined(CONTACT_LIST)
#define SEARCHES_GRID
#endif
// The compilations that test only the entries of a list marked near (common/neighbour_list.glsl):
// without sleep, the passes that take partners from the lists alone.
#if !defined(SLEEPING) && !defined(SEARCHES_GRID)
#define SCANS_NEAR
#endif
// The pass every particle (with sleep, every active one) runs, which leaves some to the others.
#if !defined(SEARCHES_GRID) && !defined(COLLIDERS_PASS)
#define EVERY_PARTICLE_PASS
#endif
// Without sleep that pass leaves the particles near a collider to the pass with the collider code.
// (With sleep the active particles are few, and each runs the collider code.)
#if defined(EVERY_PARTICLE_PASS) && !defined(SLEEPING)
#define LEAVES_COLLIDERS
#endif
// It lists particles for another pass as it runs: with sleep those that search the grid, and under
// HertzMindlin those with more slots in use than it loads (so does contacts_colliders).
#if (defined(EVERY_PARTICLE_PASS) && defined(SLEEPING)) || \
    (!defined(PAPER_LAW) && (defined(EVERY_PARTICLE_PASS) || defined(COLLIDERS_PASS)))
#define HANDS_OVER
#endif
// The contact slots a compilation loads (HertzMindlin). The loads are texel fetches, which
// llvmpipe makes for every batch of particles whether a lane has the slot in use or not, and the
// slots a pass loads are also the ones it clears. The pass every particle (with sleep, every
// active one) runs loads the first group only, as few particles have more in use. It leaves
// those to a pass that loads more: without sleep contacts_colliders (which finds no collider for
// them), which loads two groups and leaves the rarer particles with more in use still to
// contacts_search; with sleep contacts_search. The search's pass loads them all, and takes a
// particle's partners from its list as the other passes would.
#if defined(EVERY_PARTICLE_PASS)
#define LOADED_SLOTS CONTACT_SLOTS_PER_GROUP
#elif defined(COLLIDERS_PASS)
#define LOADED_SLOTS (2 * CONTACT_SLOTS_PER_GROUP)
#else
#define LOADED_SLOTS CONTACT_SLOTS
#endif
#if defined(COLLIDERS_PASS) && defined(SLEEPING)
#error "a sleeping World runs the collider code in the contacts pass"
#endif

NEIGHBOUR_LIST_TEXTURE
LIST_ORIGIN_TEXTURE
#ifdef SCANS_NEAR
LIST_NEAR_TEXTURE
#endif
CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_POSITION_TEXTURE
PARTICLE_VELOCITY_TEXTURE
COLLIDERS(readonly)
#ifndef PAPER_LAW
#ifdef SLEEPING
PARTICLE_SPIN_TEXTURE
#else
BODY_ANGULAR_VELOCITY_TEXTURE
#endif
CONTACT_PAIRS_TEXTURE
CONTACT_SLOTS_0_TEXTURE
CONTACT_SLOTS_1_TEXTURE
CONTACT_SLOTS_2_TEXTURE
#ifdef ROLLING_FRICTION
ROLLING_SLOTS_TEXTURE
#endif
#endif
#ifdef CONTACT_LIST
CONTACT_LIST_BUFFER(coherent)
#ifndef PAPER_LAW
CONTACT_SLOTS_0(readonly)
CONTACT_SLOTS_1(readonly)
CONTACT_SLOTS_2(readonly)
#endif
#else
#ifdef SLEEPING
ACTIVE_PARTICLES(readonly)
BODY_VELOCITY(writeonly)
QUIET_CHUNKS(writeonly)
#endif
PARTICLE_FORCE(writeonly)
PARTICLE_STATS(coherent)
#ifndef PAPER_LAW
PARTICLE_TORQUE(writeonly)
CONTACT_SLOTS_0(coherent)
CONTACT_SLOTS_1(coherent)
CONTACT_SLOTS_2(coherent)
#ifdef ROLLING_FRICTION
ROLLING_SLOTS_IMAGE(writeonly)
#endif
#endif
#endif
#ifdef HANDS_OVER
COUNTERS(coherent)
#else
COUNTERS(readonly)
#endif
// The lists it adds to (HANDS_OVER) and the one it runs over.
#if defined(HANDS_OVER) && (defined(SLEEPING) || defined(COLLIDERS_PASS))
SEARCH_DUE(writeonly)
#endif
#if defined(HANDS_OVER) && defined(EVERY_PARTICLE_PASS) && !defined(SLEEPING)
COLLIDERS_DUE(writeonly)
#endif
#ifdef COLLIDERS_PASS
COLLIDERS_DUE(readonly)
#endif
#ifdef SEARCHING
SEARCH_DUE(readonly)
#endif
#ifdef SLEEPING
BODY_GRID_BUILD_TEXTURE
#ifndef SEARCHING
LIST_BUILT(readonly)
#else
LIST_BUILT(coherent)
// Only the .w of a list the build passed over, and its entries: see buildPassedOverList.
NEIGHBOUR_LIST(writeonly)
LIST_ORIGIN(writeonly)
#endif
#endif
#include "common/grid.glsl"
#include "common/neighbour_list.glsl"
#ifdef HANDS_OVER
#include "common/list_decision.glsl"
#endif
#if defined(SLEEPING) && defined(SEARCHING)
vec3 searchPosition(uint id) {
  return texelFetch(listOriginTexture, int(id)).xyz;
}
#include "common/list_search.glsl"
#endif

#ifndef PAPER_LAW
// xyz: the angular velocity of particle `particle`'s body `body`; w: under SLEEPING the body's calm
// count (uint bits), which this pass changes in bodyVelocity.w: particleSpin keeps both for the
// substep. Without sleep the body's own entry, one fetch as well.
vec4 spinOf(uint particle, uint body) {
#ifdef SLEEPING
  return texelFetch(particleSpinTexture, int(particle));
#else
  return vec4(texelFetch(bodyAngularVelocityTexture, int(body)).xyz, 0.0);
#endif
}
#endif

// The particle this thread gathers for.
struct Particle {
  vec4 position;  // w: owning body (uint bits)
  vec4 velocity;  // w: inverse mass as in particleLocal (-1: static)
  vec3 spin;      // the body's angular velocity (HertzMindlin)
  uint id;
  uint body;
  uint calm;  // the body's calm count (SLEEPING)
};

// What it gathers.
vec3 force = vec3(0.0);
vec3 torque = vec3(0.0);  // about the particle's centre
uint pairContacts = 0u;
uint wallContacts = 0u;
uint guards = 0u;  // PAPER_LAW: overlaps capped; otherwise contacts that found no free slot
float largestOverlap = 0.0;
// SLEEPING: the smallest calm count among the partners; 0 for a moving collider.
uint neighbourCalm = CALM_UNBOUNDED;

// The collider's surface moves (ColliderMotion).
bool colliderMoves(Collider c) {
  return any(notEqual(c.velocity.xyz, vec3(0.0))) || any(notEqual(c.spin.xyz, vec3(0.0)));
}

#ifdef CONTACT_LIST
// What World::readContacts lists (first particle 0, every overlap, each pair once) and what the
// check of newly placed bodies lists (their particles only, overlaps beyond a tolerance, every
// pair from their side).
layout(location = 0) uniform uint listFirst;
layout(location = 1) uniform float listMinOverlap;
layout(location = 2) uniform uint listBothSides;

void record(uint a, uint b, uint bodyA, uint bodyB, uint collider, vec3 point, vec3 n, float xi,
            float normalForce, vec3 tangentialForce, vec3 spring, vec3 rollingTorque,
            vec3 rollingSpring) {
  if (xi <= listMinOverlap) return;
  uint slot = atomicAdd(contactListCount, 1u);
  if (slot >= contactListCapacity) return;
  uint at = slot * uint(CONTACT_RECORD);
  contactList[at + 0u] = vec4(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(bodyA),
                              uintBitsToFloat(bodyB));
  contactList[at + 1u] = vec4(point, xi);
  contactList[at + 2u] = vec4(n, normalForce);
  contactList[at + 3u] = vec4(tangentialForce, uintBitsToFloat(collider));
  contactList[at + 4u] = vec4(spring, 0.0);
  contactList[at + 5u] = vec4(rollingTorque, 0.0);
  contactList[at + 6u] = vec4(rollingSpring, 0.0);
}
#endif

#ifndef PAPER_LAW
// This particle's slots as the previous substep left them, the first LOADED_SLOTS (the others are
// free), held by the thread (every index below is a constant once the loops are unrolled), and
// their pair counts.
vec4 previous[LOADED_SLOTS];
#ifdef ROLLING_FRICTION
vec3 previousRolling[LOADED_SLOTS];  // their rolling springs
#endif
uvec4 previousPairs;
uint slotsUsed = 0u;
// Whether the slots name other partners than in the previous substep, or in another order: only
// then can the pair counts change (integrate_bodies.comp takes them again).
bool slotsChanged = false;

// Loads only the slots in use (previousPairs.w, which the caller fetched), through the buffer
// textures: a gather, where an SSBO load runs lane by lane on llvmpipe. Only this thread writes
// these slots, after it read them, so the texture never shows it a slot written in this pass.
void loadSlots(uint particle) {
  uint used = min(previousPairs.w, uint(CONTACT_SLOTS));
  for (uint k = 0u; k < uint(LOADED_SLOTS); ++k) {
    uint entry = slotEntry(particle, k);
    previous[k] = vec4(0.0);
    if (k < used) {
      previous[k] = k < 4u ? texelFetch(contactSlots0Texture, int(entry))
                           : (k < 8u ? texelFetch(contactSlots1Texture, int(entry))
                                     : texelFetch(contactSlots2Texture, int(entry)));
    }
#ifdef ROLLING_FRICTION
    previousRolling[k] = vec3(0.0);
    if (k < used) {
      previousRolling[k] = texelFetch(rollingSlotsTexture, rollingEntry(particle, k)).xyz;
    }
#endif
  }
}

// The spring the contact with `key` had in the previous substep (zero for a new contact), its
// rolling spring (ROLLING_FRICTION), and how many contacts joined the two bodies then (0 for a new
// contact). Notes whether it was in the slot it takes now (keepSlot: the next free one).
vec3 previousSpring(uint key, out uint pairs, out vec3 rolling) {
  vec3 spring = vec3(0.0);
  rolling = vec3(0.0);
  pairs = 0u;
  uint was = uint(CONTACT_SLOTS);
  for (uint k = 0u; k < uint(LOADED_SLOTS); ++k) {
    if (floatBitsToUint(previous[k].w) == key) {
      spring = previous[k].xyz;
#ifdef ROLLING_FRICTION
      rolling = previousRolling[k];
#endif
      pairs = slotPairs(previousPairs, k);
      was = k;
    }
  }
  if (slotsUsed < uint(CONTACT_SLOTS) && was != slotsUsed) slotsChanged = true;
  return spring;
}

#ifndef CONTACT_LIST
void storeSlot(uint particle, uint k, vec4 slot, vec3 rolling) {
  uint entry = slotEntry(particle, k);
  if (k < 4u) {
    contactSlots0[entry] = slot;
  } else if (k < 8u) {
    contactSlots1[entry] = slot;
  } else {
    contactSlots2[entry] = slot;
  }
#ifdef ROLLING_FRICTION
  imageStore(rollingSlotsImage, rollingEntry(particle, k), vec4(rolling, 0.0));
#endif
}

// Frees the slots of contacts that ended.
void clearUnusedSlots(uint particle) {
  for (uint k = 0u; k < uint(LOADED_SLOTS); ++k) {
    if (k >= slotsUsed && floatBitsToUint(previous[k].w) != SLOT_EMPTY) {
      storeSlot(particle, k, vec4(0.0), vec3(0.0));
    }
  }
}
#endif

// Writes the contact into the next free slot, in the order the contacts were found (listing, it
// only counts the slot, as the substep will take it).
void keepSlot(uint particle, uint key, vec3 spring, vec3 rolling) {
  if (slotsUsed < uint(CONTACT_SLOTS)) {
#ifndef CONTACT_LIST
    storeSlot(particle, slotsUsed, vec4(spring, uintBitsToFloat(key)), rolling);
#endif
    ++slotsUsed;
  } else {
    ++guards;  // counted (stats, viewer); the contact still acts, with a fresh spring
  }
}

// Velocity of a body's material at `point`, from one of its particles: the particle's velocity
// plus the body's spin about the particle's centre. `precise`, so that both sides of a pair
// compute each body's term with the same operations and their difference is exactly
// antisymmetric.
vec3 surfaceVelocity(vec3 particleVelocity, vec3 spin, vec3 centre, vec3 point) {
  precise vec3 v = particleVelocity + cross(spin, point - centre);
  return v;
}

// Applies one contact of the current particle: gets its spring from the previous substep,
// advances it, keeps it in a slot and adds force and torque at `point` (and, with rolling
// friction, the couple against the bodies' relative rolling, relativeSpin, whose spring it keeps
// in the same slot). A new contact is undamped for its first substep: the number n of contacts
// that joined the two bodies is counted after this substep, and taking n = 1 meanwhile would damp
// a body that meets a surface with many particles at once n times too hard (its overlap, about
// v dt, makes the damping missed this way small). Contacts that found no slot are damped with
// n = 1. rollingTorque, rollingSpring: rolling friction's couple and spring (zero without it).
MindlinResult mindlinContact(Particle self, uint key, float xi, vec3 n, vec3 point, vec3 vRel,
                             float kn, float kt0, float dampingFactor, float invMass,
                             float friction, vec3 relativeSpin, float rollingRadius,
                             out vec3 rollingTorque, out vec3 rollingSpring) {
  uint pairs;
  vec3 rolling;
  vec3 spring = previousSpring(key, pairs, rolling);
  if (pairs == 0u && slotsUsed < uint(CONTACT_SLOTS)) dampingFactor = 0.0;
  MindlinResult r = hertzMindlin(xi, n, vRel, kn, kt0, dampingFactor,
                                 float(max(pairs, 1u)) * invMass, friction, params.dt, spring);
  rollingTorque = vec3(0.0);
#ifdef ROLLING_FRICTION
  RollingResult roll = rollingResistance(relativeSpin, n, rollingRadius, r, params.dt, rolling);
  rolling = roll.spring;
  rollingTorque = roll.torque;
#endif
  rollingSpring = rolling;
  keepSlot(self.id, key, r.spring, rolling);
#ifndef CONTACT_LIST
  force += r.force;
  torque += cross(point - self.position.xyz, r.force);
#ifdef ROLLING_FRICTION
  torque += rollingTorque;
#endif
#endif
  return r;
}
#endif

#ifndef PAPER_LAW
// The contact of the current particle with particle `otherId` (closer than a diameter, of
// another body, not both immovable).
void pairContact(Particle self, uint otherId) {
  vec4 other = texelFetch(particlePositionTexture, int(otherId));
  vec4 otherVelocity = texelFetch(particleVelocityTexture, int(otherId));
  vec3 d = self.position.xyz - other.xyz;
  float dist = sqrt(dot(d, d));
  vec3 n = d / dist;
  float xi = params.particleDiameter - dist;
  largestOverlap = max(largestOverlap, xi);
  vec4 otherSpin = spinOf(otherId, floatBitsToUint(other.w));
#ifdef SLEEPING
  uint otherCalm = floatBitsToUint(otherSpin.w);
  neighbourCalm = min(neighbourCalm, otherCalm);
#ifndef CONTACT_LIST
  // Marks a sleeping partner for the next substep (every toucher writes the same value).
  if (self.calm < params.sleepSubsteps && otherCalm == params.sleepSubsteps) {
    uint otherBody = floatBitsToUint(other.w);
    bodyVelocity[otherBody].w = uintBitsToFloat(calmTouched());
    quietChunks[otherBody / COLLECT_CHUNK] = 0u;  // collect_active.comp scans its chunk again
  }
#endif
#endif
  // The contact point is the middle of the overlap: the same bits from both sides.
  precise vec3 point = 0.5 * (self.position.xyz + other.xyz);
  precise vec3 vRel = surfaceVelocity(self.velocity.xyz, self.spin, self.position.xyz, point) -
                      surfaceVelocity(otherVelocity.xyz, otherSpin.xyz, other.xyz, point);
  float invMassSum = max(self.velocity.w, 0.0) + max(otherVelocity.w, 0.0);
  vec3 rollingTorque, rollingSpring;
  MindlinResult r = mindlinContact(self, particleSlotKey(otherId), xi, n, point, vRel,
                                   params.grainStiffness, params.grainShearStiffness,
                                   params.grainDamping, invMassSum, params.friction,
                                   self.spin - otherSpin.xyz, 0.25 * params.particleDiameter,
                                   rollingTorque, rollingSpring);
#ifdef CONTACT_LIST
  // Each pair once, from the side that keeps its history (static particles keep none).
  if (listBothSides != 0u ||
      (self.velocity.w >= 0.0 && (otherVelocity.w < 0.0 || self.id < otherId))) {
    record(self.id, otherId, self.body, floatBitsToUint(other.w), 0xffffffffu,
           self.position.xyz - n * (params.particleRadius - 0.5 * xi), n, xi, r.normalForce,
           r.tangentialForce, r.spring, rollingTorque, rollingSpring);
  }
#else
  ++pairContacts;
#endif
}
#endif

#ifdef PAPER_LAW
// The contact of the current particle with particle `otherId` (closer than a diameter, of
// another body, not both immovable), as the paper has it.
void pairContact(Particle self, uint otherId) {
  vec4 other = texelFetch(particlePositionTexture, int(otherId));
  vec4 otherVelocity = texelFetch(particleVelocityTexture, int(otherId));
  vec3 d = self.position.xyz - other.xyz;
  float diameter = params.particleDiameter;
  float radius = params.particleRadius;
  float invMassSum = max(self.velocity.w, 0.0) + max(otherVelocity.w, 0.0);
  float dist2 = dot(d, d);
  float dist = sqrt(dist2);
  vec3 n = d / dist;
  float xi = diameter - dist;
  largestOverlap = max(largestOverlap, xi);
  uint otherBody = floatBitsToUint(other.w);
#ifdef CONTACT_LIST
  // Each pair once, from the side that keeps its history (static particles keep none).
  bool listed = listBothSides != 0u ||
                (self.velocity.w >= 0.0 && (otherVelocity.w < 0.0 || self.id < otherId));
#endif
  float appliedXi = xi;
  if (appliedXi > params.maxOverlap) {
    appliedXi = params.maxOverlap;  // penetration guard (paper: d/10)
    ++guards;
  }
  ContactResult r = contactForce(appliedXi, n, self.velocity.xyz - otherVelocity.xyz,
                                 params.grainStiffness, params.grainDamping, invMassSum,
                                 params.friction, params.tangentialDamping);
  vec3 spring = vec3(0.0);
#ifndef CONTACT_LIST
  force += r.force;
#endif
#ifdef CONTACT_LIST
  if (listed) {
    record(self.id, otherId, self.body, otherBody, 0xffffffffu,
           self.position.xyz - n * (radius - 0.5 * xi), n, xi, r.normalForce,
           r.tangentialForce, spring, vec3(0.0), vec3(0.0));
  }
#else
  ++pairContacts;
#endif
}
#endif

// Particle `id` touches the current particle (closer than a diameter; the lists hold only
// particles of other bodies, not both immovable).
bool touches(Particle self, uint id) {
  vec3 d = self.position.xyz - texelFetch(particlePositionTexture, int(id)).xyz;
  float dist2 = dot(d, d);
  return dist2 < params.particleDiameter * params.particleDiameter && dist2 != 0.0;
}

#ifdef SEARCHES_GRID
// The partner with the smallest id above `after` that touches the current particle, found in the
// grid of the last build (cells of d + skin: whatever touches now stood within d + skin then),
// or NO_PARTNER (`after` NO_PARTNER: the smallest of all). Only for particles with more partners
// than their list holds, and under SLEEPING in the substep a list the last build passed over is
// built (buildPassedOverList).
uint nextPartnerAfter(Particle self, uint after) {
  uint best = NO_PARTNER;
  ivec3 cell = cellOf(texelFetch(listOriginTexture, int(self.id)).xyz);
  uvec2 multipliers = hashMultipliers();
  uint stillBuild = stillGridBuild();
  for (int row = 0; row < 9; ++row) {
    uint parts = rowParts(cell, row, multipliers);
    for (uint part = 0u; part < parts; ++part) {
      uvec4 slots = rowSlots(cell, row, part, parts, multipliers);
      for (uint k = 0u; k < rowEntries(slots); ++k) {
        uint id = rowParticle(slots, k);
        if ((after != NO_PARTNER && id <= after) || id >= best) continue;
        vec4 other = texelFetch(particlePositionTexture, int(id));
        float otherInverseMass = texelFetch(particleVelocityTexture, int(id)).w;
        if (floatBitsToUint(other.w) == self.body ||
            max(self.velocity.w, 0.0) + max(otherInverseMass, 0.0) == 0.0) {
          continue;
        }
        if (touches(self, id) && rowHolds(slots, k, floatBitsToUint(other.w), stillBuild)) {
          best = id;
        }
      }
    }
  }
  return best;
}
#endif

#if defined(SLEEPING) && defined(SEARCHING)
// Builds the list of a particle that the last build passed over (it slept) for the substeps until
// the next build, so that it searches the grid in this substep only: the search of a build, from
// where the build sorted each particle (listOrigin.xyz, which no thread writes in this pass). Only
// this thread reads its list and its listOrigin.w, and not again in this pass.
void buildPassedOverList(Particle self) {
  uint ids[NEIGHBOUR_LIST_CAPACITY];
  uint count = searchList(texelFetch(listOriginTexture, int(self.id)).xyz, self.body,
                          self.velocity.w, ids);
  for (uint k = 0u; k < min(count, uint(NEIGHBOUR_LIST_CAPACITY)); ++k) {
    neighbourList[listEntry(self.id, k)] = ids[k];
  }
  listOrigin[self.id].w = uintBitsToFloat(count);
  listBuilt[self.id] = counters[COUNTER_LIST_BUILDS];
}
#endif

// Surfaces in contact found by the collider loops and not yet evaluated: the hit (normal,
// overlap), the collider's index and its face. Written and read at constant indices only: the
// number found differs between lanes, and llvmpipe writes an array at such an index lane by lane.
vec4 hits[COLLIDER_BATCH];
uint hitColliders[COLLIDER_BATCH];
uint hitFaces[COLLIDER_BATCH];

void keepHit(inout uint found, vec4 hit, uint collider, uint face) {
  for (uint j = 0u; j < uint(COLLIDER_BATCH); ++j) {
    if (j == found) {
      hits[j] = hit;
      hitColliders[j] = collider;
      hitFaces[j] = face;
    }
  }
  ++found;
}

// The surface keepHit kept as the h-th.
void takeHit(uint h, out vec4 hit, out uint collider, out uint face) {
  hit = hits[0];
  collider = hitColliders[0];
  face = hitFaces[0];
  for (uint j = 1u; j < uint(COLLIDER_BATCH); ++j) {
    if (h == j) {
      hit = hits[j];
      collider = hitColliders[j];
      face = hitFaces[j];
    }
  }
}

// One contact of the current particle with the surface `hit` of collider `c` (its face `face`).
void colliderContact(Particle self, Collider c, vec4 hit, uint face, float radius) {
  float xi = hit.w;
  largestOverlap = max(largestOverlap, xi);
  vec3 n = hit.xyz;
  vec3 point = self.position.xyz - n * (radius - 0.5 * xi);
#ifdef PAPER_LAW
  float appliedXi = xi;
  if (appliedXi > params.maxOverlap) {
    appliedXi = params.maxOverlap;  // penetration guard (paper: d/10)
    ++guards;
  }
  // The surface's velocity at the particle's centre, where this law acts.
  vec3 surface = c.velocity.xyz + cross(c.spin.xyz, self.position.xyz);
  ContactResult r = contactForce(appliedXi, n, self.velocity.xyz - surface, params.wallStiffness,
                                 c.material.z, self.velocity.w, c.material.y,
                                 params.tangentialDamping);
  vec3 spring = vec3(0.0);
  vec3 rollingTorque = vec3(0.0);
  vec3 rollingSpring = vec3(0.0);
#ifndef CONTACT_LIST
  force += r.force;
#endif
#else
#ifdef SLEEPING
  if (colliderMoves(c)) neighbourCalm = 0u;
#endif
  precise vec3 surface = c.velocity.xyz + cross(c.spin.xyz, point);
  precise vec3 vRel =
      surfaceVelocity(self.velocity.xyz, self.spin, self.position.xyz, point) - surface;
  vec3 rollingTorque, rollingSpring;
  MindlinResult r = mindlinContact(self, colliderSlotKey(c, face), xi, n, point, vRel,
                                   params.wallStiffness, params.wallShearStiffness, c.material.z,
                                   self.velocity.w, c.material.y, self.spin - c.spin.xyz,
                                   params.particleRadius, rollingTorque, rollingSpring);
  vec3 spring = r.spring;
#endif
#ifdef CONTACT_LIST
  record(self.id, 0xffffffffu, self.body, 0xffffffffu, floatBitsToUint(c.material.w), point, n,
         xi, r.normalForce, r.tangentialForce, spring, rollingTorque, rollingSpring);
#else
  ++wallContacts;
#endif
}

// Each collider type in its own loop (uniform control flow; see colliders.glsl). Every
// particle runs the loops and only movable ones take the contacts: loads inside a divergent
// branch run lane by lane on llvmpipe. The loops only find the surfaces in contact (keepHit: of
// those, the batch from the `skip`-th on, `found` of them); the law is evaluated after them,
// COLLIDER_BATCH at a time, from one place in the code (a particle touching more surfaces runs
// the loops again for the next batch). Returns how many surfaces are in contact.
uint findHits(Particle self, float radius, bool movable, uint skip, out uint found) {
  uint seen = 0u;
  found = 0u;
  for (uint k = 0u; k < params.planesEnd; ++k) {
    vec4 hit = planeHit(colliders[k], self.position.xyz, radius);
    if (movable && hit.w > 0.0) {
      if (seen >= skip && found < uint(COLLIDER_BATCH)) keepHit(found, hit, k, 0u);
      ++seen;
    }
  }
  for (uint k = params.planesEnd; k < params.boxesEnd; ++k) {
    Collider c = colliders[k];
    vec3 local = boxLocal(c, self.position.xyz);
    for (int axis = 0; axis < BOX_AXES; ++axis) {
      vec4 hit = boxHit(c, local, radius, axis);
      if (movable && hit.w > 0.0) {
        if (seen >= skip && found < uint(COLLIDER_BATCH)) {
          keepHit(found, hit, k, boxFace(c, local, axis));
        }
        ++seen;
      }
    }
  }
  for (uint k = params.boxesEnd; k < params.revolutionsEnd; ++k) {
    vec4 hit = revolutionHit(colliders[k], self.position.xyz, radius);
    if (movable && hit.w > 0.0) {
      if (seen >= skip && found < uint(COLLIDER_BATCH)) keepHit(found, hit, k, 0u);
      ++seen;
    }
  }
  return seen;
}

void main() {
#if defined(SEARCHING)
  // The particles the main pass left to this one.
  uint t = threadIndex();
  if (t >= activeListLength(ACTIVE_PASS_SEARCH)) return;
  uint i = searchDue[t];
#elif defined(COLLIDERS_PASS)
  // The particles near a collider, which the main pass left to this one.
  uint t = threadIndex();
  if (t >= activeListLength(ACTIVE_PASS_COLLIDERS)) return;
  uint i = collidersDue[t];
#elif defined(SLEEPING) && !defined(CONTACT_LIST)
  // The active particles only (collect_active.comp).
  uint t = threadIndex();
  if (t >= activeListLength(ACTIVE_PASS_CONTACTS)) return;
  uint i = activeParticles[t];
#elif defined(CONTACT_LIST)
  uint i = threadIndex() + listFirst;
  if (i >= params.particleCount) return;
#else
  uint i = threadIndex();
  if (i >= params.particleCount) return;
#endif
  Particle self;
  self.position = texelFetch(particlePositionTexture, int(i));
  self.velocity = texelFetch(particleVelocityTexture, int(i));
  self.body = floatBitsToUint(self.position.w);
  self.id = i;
  uint listed = floatBitsToUint(texelFetch(listOriginTexture, int(i)).w);
  // Static particles (rough floors) never move: nobody needs their force. Their neighbours still
  // see them, since they are in the neighbours' lists. Particles of dead bodies touch nothing.
  if (self.velocity.w < 0.0 || listed == LIST_DEAD) {
#ifndef CONTACT_LIST
    particleForce[i] = vec4(0.0);
    if (listed == LIST_DEAD) particleStats[i] = uvec4(0u, particleStats[i].yz, 0u);
#endif
    return;
  }
#ifndef PAPER_LAW
  previousPairs = texelFetch(contactPairsTexture, int(i));
  // More slots in use than this compilation loads: left to a pass that loads more (LOADED_SLOTS).
  bool manySlots = min(previousPairs.w, uint(CONTACT_SLOTS)) > uint(LOADED_SLOTS);
#else
  const bool manySlots = false;
#endif
#if defined(COLLIDERS_PASS) && defined(HANDS_OVER)
  if (manySlots) {
    searchDue[appendToPass(ACTIVE_PASS_SEARCH)] = i;  // in any order: each result is its own
    return;
  }
#endif
#ifdef EVERY_PARTICLE_PASS
  // Partners beyond the list's capacity, or a list the last build passed over (it was built while
  // the particle slept, and may miss what came near since): found in the grid, by the other pass.
  bool searches = listOverflows(listed);
#ifdef SLEEPING
  searches = searches || listBuilt[i] != counters[COUNTER_LIST_BUILDS] || manySlots;
#endif
  if (searches) {
#ifdef SLEEPING
    searchDue[appendToPass(ACTIVE_PASS_SEARCH)] = i;  // in any order: each result is its own
#endif
    return;  // without sleep the build listed it (list_build.comp)
  }
#endif
#ifdef SCANS_NEAR
  uint marks = floatBitsToUint(texelFetch(listNearTexture, int(i)).w);
#endif
#ifdef LEAVES_COLLIDERS
  if (marksNearCollider(marks)) return;  // listed by list_near.comp for contacts_colliders
#ifndef PAPER_LAW
  if (manySlots) {
    collidersDue[appendToPass(ACTIVE_PASS_COLLIDERS)] = i;  // in any order: each result is its own
    return;
  }
#endif
#endif
#ifndef PAPER_LAW
  vec4 spin = spinOf(i, self.body);
  self.spin = spin.xyz;
  self.calm = floatBitsToUint(spin.w);
  loadSlots(self.id);
#else
  self.spin = vec3(0.0);
  self.calm = 0u;
#endif
  float radius = params.particleRadius;
  // The partners in contact, in id order: the list's, then those beyond its capacity (from the
  // grid). The list is scanned first for the entries in contact (a bit each); the law is then
  // evaluated once per contact, from one place in the code.
  uint inContact = 0u;
#ifdef SCANS_NEAR
  // Only the entries marked near can touch (common/neighbour_list.glsl).
  for (uint near = nearEntries(marks); near != 0u; near &= near - 1u) {
    uint k = uint(findLSB(near));
    if (touches(self, texelFetch(neighbourListTexture, listEntry(i, k)).x)) inContact |= 1u << k;
  }
#else
  uint inList = min(listed, uint(NEIGHBOUR_LIST_CAPACITY));
  for (uint k = 0u; k < inList; ++k) {
    if (touches(self, texelFetch(neighbourListTexture, listEntry(i, k)).x)) inContact |= 1u << k;
  }
#endif
#ifdef SEARCHES_GRID
  bool beyond = listed > uint(NEIGHBOUR_LIST_CAPACITY);
#ifdef SLEEPING
  // A list the last build passed over: every partner from the grid instead, in this substep; the
  // list is built now for the next ones.
  if (listBuilt[i] != counters[COUNTER_LIST_BUILDS]) {
    inList = 0u;
    inContact = 0u;
    beyond = true;
#ifdef SEARCHING
    buildPassedOverList(self);
#endif
  }
#endif
#else
  const bool beyond = false;
#endif
  bool movable = self.velocity.w > 0.0;
  // Sleep needs the first batch of surfaces before the partners; otherwise the loop below finds
  // every batch from one call site. llvmpipe runs each inlined copy of findHits for every batch
  // of particles, whether a lane needs it or not (bench/README.md, "Code that runs anyway").
#if defined(SLEEPING) && !defined(CONTACT_LIST)
  const bool firstHitsEarly = true;
#else
  const bool firstHitsEarly = false;
#endif
  uint found = 0u;
  uint seen = 0u;
  if (firstHitsEarly) seen = findHits(self, radius, movable, 0u, found);
#ifdef SEARCHES_GRID
  uint last = beyond && inList > 0u ? texelFetch(neighbourListTexture, listEntry(i, inList - 1u)).x
                                     : NO_PARTNER;
#endif
#if defined(SLEEPING) && !defined(CONTACT_LIST)
  if (self.calm >= params.sleepSubsteps) {
    uint calm = CALM_UNBOUNDED;
    uint touching = uint(bitCount(inContact));
    for (uint bits = inContact; bits != 0u; bits &= bits - 1u) {
      uint partner = texelFetch(neighbourListTexture, listEntry(i, uint(findLSB(bits)))).x;
      calm = min(calm, floatBitsToUint(texelFetch(particleSpinTexture, int(partner)).w));
    }
#ifdef SEARCHES_GRID
    // And the partners beyond the list (all of them, for a list the last build passed over):
    // whether a sleeper's contacts stay frozen must not follow what its list holds, which follows
    // the builds (a restored World builds every list afresh).
    for (uint partner = beyond ? nextPartnerAfter(self, last) : NO_PARTNER;
         partner != NO_PARTNER; partner = nextPartnerAfter(self, partner)) {
      calm = min(calm, floatBitsToUint(texelFetch(particleSpinTexture, int(partner)).w));
      ++touching;
    }
#endif
    for (uint h = 0u; h < found; ++h) {
      vec4 hit;
      uint collider, face;
      takeHit(h, hit, collider, face);
      if (colliderMoves(colliders[collider])) calm = 0u;
    }
    // Beyond the first batch of surfaces the contacts are not all known here (they are compared
    // once counted, below).
    uint contacts = min(touching + seen, uint(CONTACT_SLOTS));
    if (contacts != min(previousPairs.w, uint(CONTACT_SLOTS))) calm = 0u;
    if (seen == found && calm >= params.sleepSubsteps) {
      particleForce[i].w = uintBitsToFloat(calm);  // the force stays the last computed
      return;
    }
    neighbourCalm = min(neighbourCalm, calm);
  }
#endif
  for (;;) {
    uint partner = NO_PARTNER;
    if (inContact != 0u) {
      partner = texelFetch(neighbourListTexture, listEntry(i, uint(findLSB(inContact)))).x;
      inContact &= inContact - 1u;
    }
#ifdef SEARCHES_GRID
    else if (beyond) {
      partner = nextPartnerAfter(self, last);
      last = partner;
      beyond = partner != NO_PARTNER;
    }
#endif
    if (partner == NO_PARTNER) break;
    pairContact(self, partner);
  }

#ifndef LEAVES_COLLIDERS
  // The surfaces in contact (findHits), a batch at a time.
  for (uint skip = 0u;; skip += uint(COLLIDER_BATCH)) {
    if (skip > 0u || !firstHitsEarly) seen = findHits(self, radius, movable, skip, found);
    for (uint h = 0u; h < found; ++h) {
      vec4 hit;
      uint collider, face;
      takeHit(h, hit, collider, face);
      colliderContact(self, colliders[collider], hit, face, radius);
    }
    if (seen <= skip + uint(COLLIDER_BATCH)) break;
  }
#endif

#ifndef CONTACT_LIST
#ifdef SLEEPING
  // A sleeper whose contacts are not those it fell asleep with wakes.
  if (self.calm >= params.sleepSubsteps && min(pairContacts + wallContacts, uint(CONTACT_SLOTS)) !=
                                       min(previousPairs.w, uint(CONTACT_SLOTS))) {
    neighbourCalm = 0u;
  }
#endif
#ifndef PAPER_LAW
  clearUnusedSlots(self.id);
  if (slotsUsed != min(previousPairs.w, uint(CONTACT_SLOTS))) slotsChanged = true;
  // w: 1 when the slots changed (integrate_bodies.comp). A sleeper that returned early above
  // leaves its slots, and this, as they were.
  particleTorque[self.id] = vec4(torque, slotsChanged ? 1.0 : 0.0);
#endif
#ifdef SLEEPING
  particleForce[self.id] = vec4(force, uintBitsToFloat(neighbourCalm));
#else
  particleForce[self.id] = vec4(force, 0.0);
#endif
  uvec4 stats = particleStats[self.id];
  stats.x = pairContacts;
  stats.y = floatBitsToUint(max(uintBitsToFloat(stats.y), largestOverlap));
  stats.z += guards;
  stats.w = wallContacts;
  particleStats[self.id] = stats;
#endif
}
