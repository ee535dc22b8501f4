#version 450
// List build, last pass: one thread per particle searches the grid just built for the particles
// within d + skin of where it stands (common/list_search.glsl) and lists the smallest ids, and
// how many there were (a particle with more finds the rest in the grid, contacts.comp). It
// records where it stands, from which the integration measures how far it moves. Static
// particles (rough floors) get no list: nobody needs their force; they are listed by the others.
// Without sleep the particles with more partners than the list holds, which the contacts pass
// leaves to contacts_search until the next build, are listed here, once, rather than by that pass
// in every substep (whose atomics and stores llvmpipe runs for every batch of particles, whether a
// lane takes them or not); list_near.comp lists those near a collider in the same way.
// Under SLEEPING a build the motion asked for runs over the active particles only
// (COUNTER_LIST_ALL, common/list_decision.glsl), and every list records the build it comes from
// (LIST_BUILT).
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"

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
SEARCH_DUE(writeonly)
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
  listOrigin[i] = vec4(self.xyz, uintBitsToFloat(alive ? count : LIST_DEAD));
#ifndef SLEEPING
  // The contacts pass gives static particles (no list) and dead ones no pass; in any order, as
  // each particle's result is its own.
  if (alive && selfInverseMass >= 0.0 && listOverflows(count)) {
    searchDue[appendToPass(ACTIVE_PASS_SEARCH)] = i;
    atomicAdd(counters[COUNTER_SEARCH_LISTED], 1u);
  }
#endif
  if (count > uint(NEIGHBOUR_LIST_CAPACITY)) atomicAdd(counters[COUNTER_LIST_OVERFLOWS], 1u);
}
