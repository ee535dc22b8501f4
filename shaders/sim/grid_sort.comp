#version 450
// List build, pass 7. One thread per bucket of each grid built sorts its particle ids ascending
// (insertion sort: buckets hold a handful of particles; there is no cap). After this pass the
// bucket order is a pure function of the particle positions: the step is deterministic.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES(coherent)
#ifdef SLEEPING
COUNTERS(readonly)
#endif
#include "common/grids_built.glsl"

void main() {
  uint t = threadIndex();
  if (t >= params.hashSize * gridsBuilt()) return;
  // Bucket t of the moving grid, or bucket t - hashSize of the still grid (gpu_buffers.def).
  uint grid = t >= params.hashSize ? 1u : 0u;
  uint offset = grid * params.particleCount;
  uint begin = texelFetch(cellStartTexture, int(t + grid)).x + offset;
  uint end = texelFetch(cellStartTexture, int(t + grid + 1u)).x + offset;
  for (uint s = begin + 1u; s < end; ++s) {
    uint id = cellParticles[s];
    uint at = s;
    while (at > begin && cellParticles[at - 1u] > id) {
      cellParticles[at] = cellParticles[at - 1u];
      --at;
    }
    cellParticles[at] = id;
  }
}
