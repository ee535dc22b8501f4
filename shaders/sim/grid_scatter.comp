#version 450
// List build, pass 6. Counting-sort scatter: each particle grid_count.comp counted takes a slot
// in its bucket's range of its grid (common/grid.glsl). The slot order inside a bucket depends
// on thread timing; grid_sort.comp makes it deterministic. Decrementing the count returns every
// bucket count to zero, so no clear pass is needed next build.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_CELL(readonly)
CELL_COUNT(coherent)
CELL_START_TEXTURE
CELL_PARTICLES(writeonly)
#ifdef SLEEPING
COUNTERS(readonly)
ACTIVE_PARTICLES(readonly)
#endif
#include "common/grid_members.glsl"

void main() {
  uint i = gridParticle(threadIndex());
  if (i == INVALID_CELL) return;
  uint cell = particleCell[i];
  if (cell == INVALID_CELL) return;
  // The still grid's buckets and slots follow the moving grid's (gpu_buffers.def, CELL_*).
  uint grid = cell >= params.hashSize ? 1u : 0u;
  uint previous = atomicAdd(cellCount[cell], 0xffffffffu);
  uint start = texelFetch(cellStartTexture, int(cell + grid)).x;
  cellParticles[start + previous - 1u + grid * params.particleCount] = i;
}
