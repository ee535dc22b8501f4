#version 450
// List build, pass 5. Counting-sort scatter: each particle takes a slot in its bucket's range. The
// slot order inside a bucket depends on thread timing; grid_sort.comp makes it deterministic.
// Decrementing the count returns every bucket count to zero, so no clear pass is needed next
// substep.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_CELL(readonly)
CELL_COUNT(coherent)
CELL_START_TEXTURE
CELL_PARTICLES(writeonly)

void main() {
  uint i = threadIndex();
  if (i >= params.particleCount) return;
  uint bucket = particleCell[i];
  if (bucket == INVALID_CELL) return;
  uint previous = atomicAdd(cellCount[bucket], 0xffffffffu);
  cellParticles[texelFetch(cellStartTexture, int(bucket)).x + previous - 1u] = i;
}
