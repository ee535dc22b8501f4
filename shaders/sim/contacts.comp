#version 450
// Pass 5. Contacts (paper eq. 9, 10): one thread per particle, in bucket order, gathers over the
// 27 neighbouring cells (as 9 runs of 3 consecutive buckets) and the implicit colliders and writes
// its total force. Gather, not scatter: no float atomics, and the neighbour order is fixed by
// grid_sort.comp, so the sum is bit-identical run to run.
//
// Compiled a second time with CONTACT_LIST defined for World::readContacts: the same loop then
// appends every contact (each particle pair once) to a list instead of writing forces.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"
#include "common/contact_law.glsl"
#include "common/colliders.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
SORTED_POSITION_TEXTURE
SORTED_VELOCITY_TEXTURE
COLLIDERS(readonly)
#ifdef CONTACT_LIST
CONTACT_LIST_BUFFER(coherent)
#else
PARTICLE_FORCE(writeonly)
PARTICLE_STATS(coherent)
#endif

#ifdef CONTACT_LIST
void record(uint a, uint b, uint bodyA, uint bodyB, uint collider, vec3 point, vec3 n, float xi,
            ContactResult r) {
  uint slot = atomicAdd(contactListCount, 1u);
  if (slot >= contactListCapacity) return;
  contactList[slot * 4u + 0u] = vec4(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(bodyA),
                                     uintBitsToFloat(bodyB));
  contactList[slot * 4u + 1u] = vec4(point, xi);
  contactList[slot * 4u + 2u] = vec4(n, r.normalForce);
  contactList[slot * 4u + 3u] = vec4(r.tangentialForce, uintBitsToFloat(collider));
}
#endif

// One collider contact of the current particle (used inside main's collider loops).
#ifdef CONTACT_LIST
#define COLLIDER_CONTACT(C, HIT)                                                                \
  {                                                                                             \
    float rawXi = HIT.w;                                                                        \
    largestOverlap = max(largestOverlap, rawXi);                                                \
    float xi = min(rawXi, maxOverlap);                                                          \
    ContactResult r = contactForce(xi, HIT.xyz, selfVelocity.xyz, wallContact.x, C.material.z,  \
                                   selfVelocity.w, C.material.y, grainContact.w);               \
    record(selfId, 0xffffffffu, selfBody, 0xffffffffu, floatBitsToUint(C.material.w),           \
           self.xyz - HIT.xyz * (radius - 0.5 * rawXi), HIT.xyz, rawXi, r);                     \
  }
#else
#define COLLIDER_CONTACT(C, HIT)                                                                \
  {                                                                                             \
    float xi = HIT.w;                                                                           \
    largestOverlap = max(largestOverlap, xi);                                                   \
    if (xi > maxOverlap) {                                                                      \
      xi = maxOverlap;                                                                          \
      ++clamps;                                                                                 \
    }                                                                                           \
    ContactResult r = contactForce(xi, HIT.xyz, selfVelocity.xyz, wallContact.x, C.material.z,  \
                                   selfVelocity.w, C.material.y, grainContact.w);               \
    force += r.force;                                                                           \
    ++wallContacts;                                                                             \
  }
#endif

void main() {
  uint i = threadIndex();
  if (i >= texelFetch(cellStartTexture, int(counts2.y)).x) return;
  vec4 self = texelFetch(sortedPositionTexture, int(i));
  vec4 selfVelocity = texelFetch(sortedVelocityTexture, int(i));
  uint selfBody = floatBitsToUint(self.w);
#ifndef CONTACT_LIST
  // Static particles (rough floors) never move: nobody needs their force. Their neighbours still
  // see them, since the gather of a sand particle reads the floor particle, not its result.
  if (selfVelocity.w < 0.0) {
    particleForce[texelFetch(cellParticlesTexture, int(i)).x] = vec4(0.0);
    return;
  }
#endif
  float radius = particleGeom.x;
  float diameter = particleGeom.y;
  float maxOverlap = particleGeom.w;
  ivec3 cell = cellOf(self.xyz);
#ifdef CONTACT_LIST
  uint selfId = texelFetch(cellParticlesTexture, int(i)).x;
#endif

  vec3 force = vec3(0.0);
  uint pairContacts = 0u;
  uint wallContacts = 0u;
  uint clamps = 0u;
  float largestOverlap = 0.0;

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
          if (floatBitsToUint(other.w) == selfBody) continue;  // own body, and self
          vec3 d = self.xyz - other.xyz;
          float dist2 = dot(d, d);
          if (dist2 >= diameter * diameter || dist2 == 0.0) continue;
          vec4 otherVelocity = texelFetch(sortedVelocityTexture, int(s));
          float invMassSum = max(selfVelocity.w, 0.0) + max(otherVelocity.w, 0.0);
          if (invMassSum == 0.0) continue;  // two immovable bodies
          float dist = sqrt(dist2);
          vec3 n = d / dist;
          float xi = diameter - dist;
          largestOverlap = max(largestOverlap, xi);
          if (xi > maxOverlap) {
            xi = maxOverlap;  // penetration guard (paper: d/10)
            ++clamps;
          }
          ContactResult r = contactForce(xi, n, selfVelocity.xyz - otherVelocity.xyz, grainContact.x,
                                         grainContact.y, invMassSum, grainContact.z, grainContact.w);
#ifdef CONTACT_LIST
          uint otherId = texelFetch(cellParticlesTexture, int(s)).x;
          if (selfId < otherId) {
            record(selfId, otherId, selfBody, floatBitsToUint(other.w), 0xffffffffu,
                   self.xyz - n * (radius - 0.5 * xi), n, diameter - dist, r);
          }
#else
          force += r.force;
          ++pairContacts;
#endif
        }
      }
    }
  }

  // Each collider type in its own loop (uniform control flow; see colliders.glsl). Every
  // particle runs the loops and only movable ones take the contacts: loads inside a divergent
  // branch run lane by lane on llvmpipe.
  bool movable = selfVelocity.w > 0.0;
  for (uint k = 0u; k < colliderEnds.x; ++k) {
    Collider c = colliders[k];
    vec4 hit = planeHit(c, self.xyz, radius);
    if (movable && hit.w > 0.0) COLLIDER_CONTACT(c, hit)
  }
  for (uint k = colliderEnds.x; k < colliderEnds.y; ++k) {
    Collider c = colliders[k];
    vec3 local = boxLocal(c, self.xyz);
    for (int axis = 0; axis < BOX_AXES; ++axis) {
      vec4 hit = boxHit(c, local, radius, axis);
      if (movable && hit.w > 0.0) COLLIDER_CONTACT(c, hit)
    }
  }
  for (uint k = colliderEnds.y; k < colliderEnds.z; ++k) {
    Collider c = colliders[k];
    vec4 hit = revolutionHit(c, self.xyz, radius);
    if (movable && hit.w > 0.0) COLLIDER_CONTACT(c, hit)
  }

#ifndef CONTACT_LIST
  uint id = texelFetch(cellParticlesTexture, int(i)).x;
  particleForce[id] = vec4(force, 0.0);
  uvec4 stats = particleStats[id];
  stats.x = pairContacts;
  stats.y = floatBitsToUint(max(uintBitsToFloat(stats.y), largestOverlap));
  stats.z += clamps;
  stats.w = wallContacts;
  particleStats[id] = stats;
#endif
}
