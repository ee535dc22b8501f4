#version 450
// List build, pass 1 of a build that fits the grid (common/grid_fit.glsl; zero groups in any
// other): the extent of the cells of the particles the build sorts (common/grid_members.glsl),
// reduced per workgroup in shared memory, then one integer atomic maximum per word (the same
// words in any order). The build's decision cleared the extent.
#include "common/layout.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
COUNTERS(coherent)
#ifdef SLEEPING
ACTIVE_PARTICLES(readonly)
#endif
#include "common/grid_members.glsl"
#include "common/grid_fit.glsl"

shared uint extent[6];

void main() {
  uint local = gl_LocalInvocationIndex;
  if (local < 6u) extent[local] = 0u;
  barrier();
  uint i = gridParticle(threadIndex());
  // As grid_count.comp: particles of dead bodies (or never born) are not sorted.
  if (i != INVALID_CELL &&
      (texelFetch(bodyInfoTexture, int(texelFetch(particleBodyTexture, int(i)).x)).z &
       BODY_ALIVE) != 0u) {
    ivec3 cell = cellOf(texelFetch(particlePositionTexture, int(i)).xyz);
    for (int axis = 0; axis < 3; ++axis) {
      atomicMax(extent[axis], extentKey(cell[axis]));
      atomicMax(extent[3 + axis], ~extentKey(cell[axis]));
    }
  }
  barrier();
  if (local < 6u && extent[local] != 0u) {
    atomicMax(counters[COUNTER_GRID_EXTENT + local], extent[local]);
  }
}
