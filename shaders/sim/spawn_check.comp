#version 450
// Emitted granules whose place is taken (a grain thrown back up under the emitter): one thread
// per particle of the granules an emitter has just added, before the substep that first moves
// them. Each gathers over its 27 neighbouring cells in the grid of the previous substep (its
// positions moved by one substep since: far less than a diameter) and, when it overlaps a
// particle of another body, the granule is not born: it is marked dead and counted. The emitter
// cannot see the sand, and a granule born inside another one would lock into it (no force cap
// pushes it out gently). Integer atomics only: the result does not depend on thread order.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
SORTED_POSITION_TEXTURE
BODY_POSITION_TEXTURE
BODY_ORIENTATION_TEXTURE
PARTICLE_LOCAL_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO(coherent)
COUNTERS(coherent)
#include "common/particle_offset.glsl"

// The first new particle and how many there are.
layout(location = 0) uniform uvec2 spawned;

void main() {
  uint t = threadIndex();
  if (t >= spawned.y) return;
  uint i = spawned.x + t;
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  vec3 position =
      texelFetch(bodyPositionTexture, int(body)).xyz + particleOffset(int(body), int(i));
  float diameter = particleGeom.y;
  ivec3 cell = cellOf(position);
  bool taken = false;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        uint bucket = bucketOf(cell + ivec3(dx, dy, dz));
        uint begin = texelFetch(cellStartTexture, int(bucket)).x;
        uint end = texelFetch(cellStartTexture, int(bucket + 1u)).x;
        for (uint s = begin; s < end; ++s) {
          vec4 other = texelFetch(sortedPositionTexture, int(s));
          vec3 d = position - other.xyz;
          if (floatBitsToUint(other.w) != body && dot(d, d) < diameter * diameter) taken = true;
        }
      }
    }
  }
  if (!taken) return;
  uint before = atomicAnd(bodyInfo[body].z, ~BODY_ALIVE);
  if ((before & BODY_ALIVE) != 0u) atomicAdd(counters[COUNTER_SPAWN_TAKEN], 1u);
}
