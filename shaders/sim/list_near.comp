#version 450
// Pass 2b, without sleep: one thread per particle marks the entries of its list within
// d + near skin of where it stands (listNear, common/neighbour_list.glsl) and records that place,
// from which the integration measures how far it moves. It also marks a movable particle within
// half the near skin of a collider's surface (LIST_NEAR_COLLIDER) and lists it for
// contacts_colliders until the next marking: the others touch no collider before then, and only
// the listed ones run the collider code. Listed here, once, rather than by the contacts pass in
// every substep, whose atomics and stores llvmpipe runs for every batch of particles. Indirect:
// after every build, and when some particle moved more than half the near skin since the last
// marking (list_check.comp decides); zero groups otherwise.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/colliders.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
PARTICLE_VELOCITY_TEXTURE
NEIGHBOUR_LIST_TEXTURE
LIST_ORIGIN_TEXTURE
LIST_NEAR(writeonly)
COLLIDERS(readonly)
COLLIDERS_DUE(writeonly)
COUNTERS(coherent)
#include "common/neighbour_list.glsl"
#include "common/list_decision.glsl"

// Whether the surface of some collider comes within `reach` of p (a sphere of that radius
// overlaps it). Every hit function is the radius less a distance that changes no faster than p
// moves, so a particle that moves less than reach - r touches no collider this misses.
bool nearCollider(vec3 p, float reach) {
  float deepest = 0.0;
  for (uint k = 0u; k < params.planesEnd; ++k) {
    deepest = max(deepest, planeHit(colliders[k], p, reach).w);
  }
  for (uint k = params.planesEnd; k < params.boxesEnd; ++k) {
    vec3 local = boxLocal(colliders[k], p);
    for (int axis = 0; axis < BOX_AXES; ++axis) {
      deepest = max(deepest, boxHit(colliders[k], local, reach, axis).w);
    }
  }
  for (uint k = params.boxesEnd; k < params.revolutionsEnd; ++k) {
    deepest = max(deepest, revolutionHit(colliders[k], p, reach).w);
  }
  return deepest > 0.0;
}

void main() {
  uint i = threadIndex();
  if (i >= params.particleCount) return;
  vec3 self = texelFetch(particlePositionTexture, int(i)).xyz;
  uint listed = floatBitsToUint(texelFetch(listOriginTexture, int(i)).w);
  bool dead = listed == LIST_DEAD;
  uint inList = dead ? 0u : min(listed, uint(NEIGHBOUR_LIST_CAPACITY));
  uint marks = 0u;
  for (uint k = 0u; k < inList; ++k) {
    uint partner = texelFetch(neighbourListTexture, listEntry(i, k)).x;
    vec3 d = self - texelFetch(particlePositionTexture, int(partner)).xyz;
    if (dot(d, d) < params.nearReachSquared) marks |= 1u << k;
  }
  // Within r + near skin / 2 = (d + near skin) / 2: a marking is asked for a hair before a
  // particle has moved half the near skin. A particle beyond its list's capacity is the search's.
  bool movable = texelFetch(particleVelocityTexture, int(i)).w > 0.0;
  if (!dead && movable && !listOverflows(listed) &&
      nearCollider(self, 0.5 * sqrt(params.nearReachSquared))) {
    marks |= LIST_NEAR_COLLIDER;
    // In any order, as each particle's result is its own.
    collidersDue[appendToPass(ACTIVE_PASS_COLLIDERS)] = i;
    atomicAdd(counters[COUNTER_COLLIDERS_LISTED], 1u);
  }
  listNear[i] = vec4(self, uintBitsToFloat(marks));
}
