#version 450
// List build, pass 6. One thread per bucket sorts its particle ids ascending (insertion sort:
// buckets hold a handful of particles; there is no cap). After this pass the bucket order is a pure
// function of the particle positions: the step is deterministic.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES(coherent)

void main() {
  uint bucket = threadIndex();
  if (bucket >= params.hashSize) return;
  uint begin = texelFetch(cellStartTexture, int(bucket)).x;
  uint end = texelFetch(cellStartTexture, int(bucket + 1u)).x;
  for (uint s = begin + 1u; s < end; ++s) {
    uint id = cellParticles[s];
    uint t = s;
    while (t > begin && cellParticles[t - 1u] > id) {
      cellParticles[t] = cellParticles[t - 1u];
      --t;
    }
    cellParticles[t] = id;
  }
}
