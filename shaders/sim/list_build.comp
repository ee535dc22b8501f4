#version 450
// List build, last pass: one thread per particle searches the grid just built for the particles
// within d + skin of where it stands (common/list_search.glsl) and lists the smallest ids, and
// how many there were (a particle with more finds the rest in the grid, contacts.comp). It
// records where it stands, from which the integration measures how far it moves. Static
// particles (rough floors) get no list: nobody needs their force; they are listed by the others.
// Without sleep a movable particle within half the skin of a collider's surface is marked
// (LIST_NEAR_COLLIDER, common/neighbour_list.glsl): only such particles run the collider code
// until the next build. (With sleep contacts.comp keeps the collider code for every particle.)
// The particles that the contacts pass leaves to another until the next build are listed here,
// once, rather than by that pass in every substep (whose atomics and stores llvmpipe runs for
// every batch of particles, whether a lane takes them or not): those with more partners than the
// list holds to contacts_search, the others marked near a collider to contacts_colliders.
// Under SLEEPING a build the motion asked for runs over the active particles only
// (COUNTER_LIST_ALL, common/list_decision.glsl), and every list records the build it comes from
// (LIST_BUILT).
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"
#include "common/colliders.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_POSITION_TEXTURE
PARTICLE_VELOCITY_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
NEIGHBOUR_LIST(writeonly)
LIST_ORIGIN(writeonly)
COUNTERS(coherent)
#ifndef SLEEPING
COLLIDERS(readonly)
SEARCH_DUE(writeonly)
COLLIDERS_DUE(writeonly)
#endif
#ifdef SLEEPING
ACTIVE_PARTICLES(readonly)
LIST_BUILT(writeonly)
BODY_GRID_BUILD_TEXTURE
#endif
#include "common/grid.glsl"
#include "common/neighbour_list.glsl"
#include "common/list_decision.glsl"

vec3 searchPosition(uint id) {
  return texelFetch(particlePositionTexture, int(id)).xyz;
}
#include "common/list_search.glsl"

#ifndef SLEEPING
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
#endif

void main() {
#ifdef SLEEPING
  uint t = threadIndex();
  bool every = counters[COUNTER_LIST_ALL] != 0u;
  if (t >= (every ? params.particleCount : activeListLength(ACTIVE_PASS_CONTACTS))) {
    return;
  }
  uint i = every ? t : activeParticles[t];
  listBuilt[i] = counters[COUNTER_LIST_BUILDS];
#else
  uint i = threadIndex();
  if (i >= params.particleCount) return;
#endif
  vec4 self = texelFetch(particlePositionTexture, int(i));
  float selfInverseMass = texelFetch(particleVelocityTexture, int(i)).w;
  // The owner from particleBody, as grid_count.comp: a granule never born has no state.
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  bool alive = (texelFetch(bodyInfoTexture, int(body)).z & BODY_ALIVE) != 0u;
  uint ids[NEIGHBOUR_LIST_CAPACITY];
  uint count = alive && selfInverseMass >= 0.0 ? searchList(self.xyz, body, selfInverseMass, ids)
                                                : 0u;
  for (uint k = 0u; k < min(count, uint(NEIGHBOUR_LIST_CAPACITY)); ++k) {
    neighbourList[listEntry(i, k)] = ids[k];
  }
  uint listed = count;
#ifndef SLEEPING
  // Within r + skin / 2 = (d + skin) / 2: a particle asks for a build a hair before it has moved
  // half the skin, as for its partners.
  if (alive && selfInverseMass > 0.0 &&
      nearCollider(self.xyz, 0.5 * sqrt(params.listReachSquared))) {
    listed |= LIST_NEAR_COLLIDER;
  }
#endif
  listOrigin[i] = vec4(self.xyz, uintBitsToFloat(alive ? listed : LIST_DEAD));
#ifndef SLEEPING
  // The contacts pass gives static particles (no list) and dead ones no pass; in any order, as
  // each particle's result is its own.
  if (alive && selfInverseMass >= 0.0) {
    if (listOverflows(listed)) {
      searchDue[appendToPass(ACTIVE_PASS_SEARCH)] = i;
      atomicAdd(counters[COUNTER_SEARCH_LISTED], 1u);
    } else if ((listed & LIST_NEAR_COLLIDER) != 0u) {
      collidersDue[appendToPass(ACTIVE_PASS_COLLIDERS)] = i;
      atomicAdd(counters[COUNTER_COLLIDERS_LISTED], 1u);
    }
  }
#endif
  if (count > uint(NEIGHBOUR_LIST_CAPACITY)) atomicAdd(counters[COUNTER_LIST_OVERFLOWS], 1u);
}
