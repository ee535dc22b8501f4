#version 450
// Pass 5. Contacts: one thread per particle, in bucket order, gathers over the 27 neighbouring
// cells (as 9 runs of 3 consecutive buckets) and the implicit colliders and writes its total
// force (and, under ContactLaw::HertzMindlin, the torque about its centre and its contact
// slots). Gather, not scatter: no float atomics, and the neighbour order is fixed by
// grid_sort.comp, so the sum is bit-identical run to run.
//
// The loop over the neighbouring cells only finds the partners (closer than a diameter, of another
// body, not both immovable) and lists them in order; the contacts are then evaluated from that
// list, PARTNER_BATCH at a time. In SIMD lanes that scan different cells, the law's arithmetic
// then runs once per partner rather than once per candidate any lane has in contact, which was
// most of the kernel's time; the order of the sum, and so every bit, is the grid's as before.
//
// The law is chosen when the kernel is compiled: PAPER_LAW selects the paper's (eq. 9, 10;
// contactForce in common/contact_law.glsl), otherwise Hertz-Mindlin with history (hertzMindlin,
// and common/contact_slots.glsl). Compiled a second time with CONTACT_LIST defined for
// World::readContacts: the same loop then appends every contact (each particle pair once, from
// the side that keeps its history) to a list instead of writing forces and slots.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"
#include "common/contact_law.glsl"
#include "common/colliders.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

// Partners listed before their contacts are evaluated (see above); a particle with more is
// evaluated in several batches, in the same order.
#define PARTNER_BATCH 16

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
SORTED_POSITION_TEXTURE
SORTED_VELOCITY_TEXTURE
COLLIDERS(readonly)
#ifndef PAPER_LAW
SORTED_SPIN_TEXTURE
CONTACT_PAIRS_TEXTURE
#endif
#ifdef CONTACT_LIST
CONTACT_LIST_BUFFER(coherent)
#ifndef PAPER_LAW
CONTACT_SLOTS_0(readonly)
CONTACT_SLOTS_1(readonly)
CONTACT_SLOTS_2(readonly)
#endif
#else
PARTICLE_FORCE(writeonly)
PARTICLE_STATS(coherent)
#ifndef PAPER_LAW
PARTICLE_TORQUE(writeonly)
CONTACT_SLOTS_0(coherent)
CONTACT_SLOTS_1(coherent)
CONTACT_SLOTS_2(coherent)
#endif
#endif

// The particle this thread gathers for.
struct Particle {
  vec4 position;  // w: owning body (uint bits)
  vec4 velocity;  // w: inverse mass as in particleLocal (-1: static)
  vec3 spin;      // the body's angular velocity (HertzMindlin)
  uint id;
  uint body;
};

// What it gathers.
vec3 force = vec3(0.0);
vec3 torque = vec3(0.0);  // about the particle's centre
uint pairContacts = 0u;
uint wallContacts = 0u;
uint guards = 0u;  // PAPER_LAW: overlaps capped; otherwise contacts that found no free slot
float largestOverlap = 0.0;

#ifdef CONTACT_LIST
void record(uint a, uint b, uint bodyA, uint bodyB, uint collider, vec3 point, vec3 n, float xi,
            float normalForce, vec3 tangentialForce, vec3 spring) {
  uint slot = atomicAdd(contactListCount, 1u);
  if (slot >= contactListCapacity) return;
  contactList[slot * 5u + 0u] = vec4(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(bodyA),
                                     uintBitsToFloat(bodyB));
  contactList[slot * 5u + 1u] = vec4(point, xi);
  contactList[slot * 5u + 2u] = vec4(n, normalForce);
  contactList[slot * 5u + 3u] = vec4(tangentialForce, uintBitsToFloat(collider));
  contactList[slot * 5u + 4u] = vec4(spring, 0.0);
}
#endif

#ifndef PAPER_LAW
// This particle's slots as the previous substep left them, held by the thread (every index
// below is a constant once the loops are unrolled), and their pair counts.
vec4 previous[CONTACT_SLOTS];
uvec4 previousPairs;
uint slotsUsed = 0u;

// Loads only the slots in use (contactPairs.w): an SSBO load per lane is what a slot costs here.
void loadSlots(uint particle) {
  previousPairs = texelFetch(contactPairsTexture, int(particle));
  uint used = min(previousPairs.w, uint(CONTACT_SLOTS));
  for (uint k = 0u; k < uint(CONTACT_SLOTS); ++k) {
    uint entry = slotEntry(particle, k);
    previous[k] = vec4(0.0);
    if (k < used) {
      previous[k] = k < 4u ? contactSlots0[entry]
                           : (k < 8u ? contactSlots1[entry] : contactSlots2[entry]);
    }
  }
}

// The spring the contact with `key` had in the previous substep (zero for a new contact), and
// how many contacts joined the two bodies then (0 for a new contact).
vec3 previousSpring(uint key, out uint pairs) {
  vec3 spring = vec3(0.0);
  pairs = 0u;
  for (uint k = 0u; k < uint(CONTACT_SLOTS); ++k) {
    if (floatBitsToUint(previous[k].w) == key) {
      spring = previous[k].xyz;
      pairs = slotPairs(previousPairs, k);
    }
  }
  return spring;
}

#ifndef CONTACT_LIST
void storeSlot(uint particle, uint k, vec4 slot) {
  uint entry = slotEntry(particle, k);
  if (k < 4u) {
    contactSlots0[entry] = slot;
  } else if (k < 8u) {
    contactSlots1[entry] = slot;
  } else {
    contactSlots2[entry] = slot;
  }
}

// Writes the contact into the next free slot, in the order the contacts were found.
void keepSlot(uint particle, uint key, vec3 spring) {
  if (slotsUsed < uint(CONTACT_SLOTS)) {
    storeSlot(particle, slotsUsed, vec4(spring, uintBitsToFloat(key)));
    ++slotsUsed;
  } else {
    ++guards;  // counted (stats, viewer); the contact still acts, with a fresh spring
  }
}

// Frees the slots of contacts that ended.
void clearUnusedSlots(uint particle) {
  for (uint k = 0u; k < uint(CONTACT_SLOTS); ++k) {
    if (k >= slotsUsed && floatBitsToUint(previous[k].w) != SLOT_EMPTY) {
      storeSlot(particle, k, vec4(0.0));
    }
  }
}
#endif

// Velocity of a body's material at `point`, from one of its particles: the particle's velocity
// plus the body's spin about the particle's centre. `precise`, so that both sides of a pair
// compute each body's term with the same operations and their difference is exactly
// antisymmetric.
vec3 surfaceVelocity(vec3 particleVelocity, vec3 spin, vec3 centre, vec3 point) {
  precise vec3 v = particleVelocity + cross(spin, point - centre);
  return v;
}

// Applies one contact of the current particle: gets its spring from the previous substep,
// advances it (or, listing, takes it as stored) and adds force and torque at `point`. A new
// contact is undamped for its first substep: the number n of contacts that joined the two
// bodies is counted after this substep, and taking n = 1 meanwhile would damp a body that meets
// a surface with many particles at once n times too hard (its overlap, about v dt, makes the
// damping missed this way small). Contacts that found no slot are damped with n = 1.
MindlinResult mindlinContact(Particle self, uint key, float xi, vec3 n, vec3 point, vec3 vRel,
                             float kn, float kt0, float dampingFactor, float invMass,
                             float friction) {
  uint pairs;
  vec3 spring = previousSpring(key, pairs);
#ifdef CONTACT_LIST
  const bool advance = false;  // the stored spring is already this substep's
#else
  const bool advance = true;
  if (pairs == 0u && slotsUsed < uint(CONTACT_SLOTS)) dampingFactor = 0.0;
#endif
  MindlinResult r = hertzMindlin(xi, n, vRel, kn, kt0, dampingFactor,
                                 float(max(pairs, 1u)) * invMass, friction, gravityDt.w, spring,
                                 advance);
#ifndef CONTACT_LIST
  force += r.force;
  torque += cross(point - self.position.xyz, r.force);
  keepSlot(self.id, key, r.spring);
#endif
  return r;
}
#endif

#ifndef PAPER_LAW
// The contact of the current particle with the particle in bucket-ordered slot `s` (closer than
// a diameter, of another body, not both immovable).
void pairContact(Particle self, uint s) {
  vec4 other = texelFetch(sortedPositionTexture, int(s));
  vec4 otherVelocity = texelFetch(sortedVelocityTexture, int(s));
  vec3 d = self.position.xyz - other.xyz;
  float dist = sqrt(dot(d, d));
  vec3 n = d / dist;
  float xi = particleGeom.y - dist;
  largestOverlap = max(largestOverlap, xi);
  vec4 otherSpin = texelFetch(sortedSpinTexture, int(s));
  uint otherId = floatBitsToUint(otherSpin.w);
  // The contact point is the middle of the overlap: the same bits from both sides.
  precise vec3 point = 0.5 * (self.position.xyz + other.xyz);
  precise vec3 vRel = surfaceVelocity(self.velocity.xyz, self.spin, self.position.xyz, point) -
                      surfaceVelocity(otherVelocity.xyz, otherSpin.xyz, other.xyz, point);
  float invMassSum = max(self.velocity.w, 0.0) + max(otherVelocity.w, 0.0);
  MindlinResult r = mindlinContact(self, particleSlotKey(otherId), xi, n, point, vRel,
                                   grainContact.x, shearContact.x, grainContact.y, invMassSum,
                                   grainContact.z);
#ifdef CONTACT_LIST
  // Each pair once, from the side that keeps its history (static particles keep none).
  if (self.velocity.w >= 0.0 && (otherVelocity.w < 0.0 || self.id < otherId)) {
    record(self.id, otherId, self.body, floatBitsToUint(other.w), 0xffffffffu,
           self.position.xyz - n * (particleGeom.x - 0.5 * xi), n, xi, r.normalForce,
           r.tangentialForce, r.spring);
  }
#else
  ++pairContacts;
#endif
}
#endif

#ifdef PAPER_LAW
// The contact of the current particle with the particle in bucket-ordered slot `s` (closer than
// a diameter, of another body, not both immovable), as the paper has it.
void pairContact(Particle self, uint s) {
  vec4 other = texelFetch(sortedPositionTexture, int(s));
  vec4 otherVelocity = texelFetch(sortedVelocityTexture, int(s));
  vec3 d = self.position.xyz - other.xyz;
  float diameter = particleGeom.y;
  float radius = particleGeom.x;
  float invMassSum = max(self.velocity.w, 0.0) + max(otherVelocity.w, 0.0);
  float dist2 = dot(d, d);
  float dist = sqrt(dist2);
  vec3 n = d / dist;
  float xi = diameter - dist;
  largestOverlap = max(largestOverlap, xi);
  uint otherId = texelFetch(cellParticlesTexture, int(s)).x;
  uint otherBody = floatBitsToUint(other.w);
#ifdef CONTACT_LIST
  // Each pair once, from the side that keeps its history (static particles keep none).
  bool listed = self.velocity.w >= 0.0 && (otherVelocity.w < 0.0 || self.id < otherId);
#endif
  float appliedXi = xi;
  if (appliedXi > particleGeom.w) {
    appliedXi = particleGeom.w;  // penetration guard (paper: d/10)
    ++guards;
  }
  ContactResult r = contactForce(appliedXi, n, self.velocity.xyz - otherVelocity.xyz,
                                 grainContact.x, grainContact.y, invMassSum,
                                 grainContact.z, grainContact.w);
  vec3 spring = vec3(0.0);
#ifndef CONTACT_LIST
  force += r.force;
#endif
#ifdef CONTACT_LIST
  if (listed) {
    record(self.id, otherId, self.body, otherBody, 0xffffffffu,
           self.position.xyz - n * (radius - 0.5 * xi), n, xi, r.normalForce,
           r.tangentialForce, spring);
  }
#else
  ++pairContacts;
#endif
}
#endif

// Partners found by the cell loop and not yet evaluated: bucket-ordered slots.
uint partners[PARTNER_BATCH];

// Evaluates the first `count` partners in the order they were found.
void evaluatePartners(Particle self, uint count) {
  for (uint k = 0u; k < count; ++k) pairContact(self, partners[k]);
}

// One contact of the current particle with the surface `hit` of collider `c` (its face `face`).
void colliderContact(Particle self, Collider c, vec4 hit, uint face, float radius) {
  float xi = hit.w;
  largestOverlap = max(largestOverlap, xi);
  vec3 n = hit.xyz;
  vec3 point = self.position.xyz - n * (radius - 0.5 * xi);
#ifdef PAPER_LAW
  float appliedXi = xi;
  if (appliedXi > particleGeom.w) {
    appliedXi = particleGeom.w;  // penetration guard (paper: d/10)
    ++guards;
  }
  // The surface's velocity at the particle's centre, where this law acts.
  vec3 surface = c.velocity.xyz + cross(c.spin.xyz, self.position.xyz);
  ContactResult r = contactForce(appliedXi, n, self.velocity.xyz - surface, wallContact.x,
                                 c.material.z, self.velocity.w, c.material.y, grainContact.w);
  vec3 spring = vec3(0.0);
#ifndef CONTACT_LIST
  force += r.force;
#endif
#else
  precise vec3 surface = c.velocity.xyz + cross(c.spin.xyz, point);
  precise vec3 vRel =
      surfaceVelocity(self.velocity.xyz, self.spin, self.position.xyz, point) - surface;
  MindlinResult r = mindlinContact(self, colliderSlotKey(c, face), xi, n, point, vRel,
                                   wallContact.x, shearContact.y, c.material.z, self.velocity.w,
                                   c.material.y);
  vec3 spring = r.spring;
#endif
#ifdef CONTACT_LIST
  record(self.id, 0xffffffffu, self.body, 0xffffffffu, floatBitsToUint(c.material.w), point, n,
         xi, r.normalForce, r.tangentialForce, spring);
#else
  ++wallContacts;
#endif
}

void main() {
  uint i = threadIndex();
  if (i >= texelFetch(cellStartTexture, int(counts2.y)).x) return;
  Particle self;
  self.position = texelFetch(sortedPositionTexture, int(i));
  self.velocity = texelFetch(sortedVelocityTexture, int(i));
  self.body = floatBitsToUint(self.position.w);
  self.id = texelFetch(cellParticlesTexture, int(i)).x;
#ifndef CONTACT_LIST
  // Static particles (rough floors) never move: nobody needs their force. Their neighbours still
  // see them, since the gather of a sand particle reads the floor particle, not its result.
  if (self.velocity.w < 0.0) {
    particleForce[self.id] = vec4(0.0);
    return;
  }
#endif
#ifndef PAPER_LAW
  self.spin = texelFetch(sortedSpinTexture, int(i)).xyz;
  loadSlots(self.id);
#else
  self.spin = vec3(0.0);
#endif
  float radius = particleGeom.x;
  float diameter = particleGeom.y;
  ivec3 cell = cellOf(self.position.xyz);
  // Partners are listed PARTNER_BATCH at a time: a particle with more scans the cells again
  // for the next batch, so that every partner is evaluated once and in the grid's order.
  for (uint skip = 0u;; skip += uint(PARTNER_BATCH)) {
    uint seen = 0u;   // partners met in this scan
    uint found = 0u;  // of them, listed for this batch
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        uint centre = bucketOf(cell + ivec3(0, dy, dz));
        uint first = (centre - 1u) & counts.z;
        uint last = (centre + 1u) & counts.z;
        // The three x-neighbours are consecutive buckets unless the row wraps around the table.
        bool contiguous = first < last;
        for (uint part = 0u; part < (contiguous ? 1u : 3u); ++part) {
          uint bucketBegin = contiguous ? first : ((centre + part - 1u) & counts.z);
          uint bucketEnd = contiguous ? last : bucketBegin;
          uint begin = texelFetch(cellStartTexture, int(bucketBegin)).x;
          uint end = texelFetch(cellStartTexture, int(bucketEnd + 1u)).x;
          for (uint s = begin; s < end; ++s) {
            vec4 other = texelFetch(sortedPositionTexture, int(s));
            if (floatBitsToUint(other.w) == self.body) continue;  // own body, and self
            vec3 d = self.position.xyz - other.xyz;
            float dist2 = dot(d, d);
            if (dist2 >= diameter * diameter || dist2 == 0.0) continue;
            vec4 otherVelocity = texelFetch(sortedVelocityTexture, int(s));
            float invMassSum = max(self.velocity.w, 0.0) + max(otherVelocity.w, 0.0);
            if (invMassSum == 0.0) continue;  // two immovable bodies
            if (seen >= skip && found < uint(PARTNER_BATCH)) {
              partners[found] = s;
              ++found;
            }
            ++seen;
          }
        }
      }
    }
    evaluatePartners(self, found);
    if (seen <= skip + uint(PARTNER_BATCH)) break;
  }

  // Each collider type in its own loop (uniform control flow; see colliders.glsl). Every
  // particle runs the loops and only movable ones take the contacts: loads inside a divergent
  // branch run lane by lane on llvmpipe.
  bool movable = self.velocity.w > 0.0;
  for (uint k = 0u; k < colliderEnds.x; ++k) {
    Collider c = colliders[k];
    vec4 hit = planeHit(c, self.position.xyz, radius);
    if (movable && hit.w > 0.0) colliderContact(self, c, hit, 0u, radius);
  }
  for (uint k = colliderEnds.x; k < colliderEnds.y; ++k) {
    Collider c = colliders[k];
    vec3 local = boxLocal(c, self.position.xyz);
    for (int axis = 0; axis < BOX_AXES; ++axis) {
      vec4 hit = boxHit(c, local, radius, axis);
      if (movable && hit.w > 0.0) colliderContact(self, c, hit, boxFace(c, local, axis), radius);
    }
  }
  for (uint k = colliderEnds.y; k < colliderEnds.z; ++k) {
    Collider c = colliders[k];
    vec4 hit = revolutionHit(c, self.position.xyz, radius);
    if (movable && hit.w > 0.0) colliderContact(self, c, hit, 0u, radius);
  }

#ifndef CONTACT_LIST
#ifndef PAPER_LAW
  clearUnusedSlots(self.id);
  particleTorque[self.id] = vec4(torque, 0.0);
#endif
  particleForce[self.id] = vec4(force, 0.0);
  uvec4 stats = particleStats[self.id];
  stats.x = pairContacts;
  stats.y = floatBitsToUint(max(uintBitsToFloat(stats.y), largestOverlap));
  stats.z += guards;
  stats.w = wallContacts;
  particleStats[self.id] = stats;
#endif
}
