#version 450
// List build, pass 5. Counting-sort scatter: each particle takes a slot in its bucket's range. The
// slot order inside a bucket depends on thread timing; grid_sort.comp makes it deterministic.
// Decrementing the count returns every bucket count to zero, so no clear pass is needed next
// substep. The particles are those grid_count.comp counted (common/grid_members.glsl); the still
// grid's finds each bucket again from the position, which has not changed since.
#include "common/layout.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_COUNT(coherent)
CELL_START_TEXTURE
CELL_PARTICLES(writeonly)
#ifdef STILL_GRID
PARTICLE_POSITION_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
BODY_GRID_BUILD(readonly)
COUNTERS(readonly)
#else
PARTICLE_CELL(readonly)
#endif
#if defined(SLEEPING) && !defined(STILL_GRID)
ACTIVE_PARTICLES(readonly)
RECENT_PARTICLES(readonly)
COUNTERS(readonly)
#endif
#include "common/grid_members.glsl"

void main() {
  uint i = gridParticle(threadIndex());
  if (i == INVALID_CELL) return;
#ifdef STILL_GRID
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  if (!inGrid(body, texelFetch(bodyInfoTexture, int(body)).z)) return;
  uint bucket = bucketOf(cellOf(texelFetch(particlePositionTexture, int(i)).xyz));
#else
  uint bucket = particleCell[i];
  if (bucket == INVALID_CELL) return;
#endif
  uint previous = atomicAdd(cellCount[bucket], 0xffffffffu);
  cellParticles[texelFetch(cellStartTexture, int(bucket)).x + previous - 1u] = i;
}
