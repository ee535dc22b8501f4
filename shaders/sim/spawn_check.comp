#version 450
// Emitted granules whose place is taken (a grain thrown back up under the emitter): one thread
// per particle of the granules an emitter has just added, before the substep that first moves
// them. Each gathers over its 27 neighbouring cells in the grid of the last list build (cells of
// d + skin: a particle within d of it now stood within d + skin/2 then, in one of those cells)
// and, when it overlaps a particle of another body at its present position, the granule is not
// born: it is marked dead and counted. The emitter
// cannot see the sand, and a granule born inside another one would lock into it (no force cap
// pushes it out gently). Integer atomics only: the result does not depend on thread order.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_POSITION_TEXTURE
BODY_POSITION_TEXTURE
BODY_ORIENTATION_TEXTURE
PARTICLE_LOCAL_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO(coherent)
COUNTERS(coherent)
#ifdef SLEEPING
BODY_GRID_BUILD_TEXTURE
#endif
#include "common/particle_offset.glsl"
#include "common/grid.glsl"

// The first new particle and how many there are.
layout(location = 0) uniform uvec2 spawned;

void main() {
  uint t = threadIndex();
  if (t >= spawned.y) return;
  uint i = spawned.x + t;
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  vec3 position =
      texelFetch(bodyPositionTexture, int(body)).xyz + particleOffset(int(body), int(i));
  float diameter = params.particleDiameter;
  ivec3 cell = cellOf(position);
  uvec2 multipliers = hashMultipliers();
  bool taken = false;
  uint stillBuild = stillGridBuild();
  for (int row = 0; row < 9; ++row) {
    uint parts = rowParts(cell, row, multipliers);
    for (uint part = 0u; part < parts; ++part) {
      uvec4 slots = rowSlots(cell, row, part, parts, multipliers);
      for (uint k = 0u; k < rowEntries(slots); ++k) {
        vec4 other = texelFetch(particlePositionTexture, int(rowParticle(slots, k)));
        vec3 d = position - other.xyz;
        uint owner = floatBitsToUint(other.w);
        if (owner != body && dot(d, d) < diameter * diameter &&
            rowHolds(slots, k, owner, stillBuild)) {
          taken = true;
        }
      }
    }
  }
  if (!taken) return;
  uint before = atomicAnd(bodyInfo[body].z, ~BODY_ALIVE);
  if ((before & BODY_ALIVE) != 0u) atomicAdd(counters[COUNTER_SPAWN_TAKEN], 1u);
}
