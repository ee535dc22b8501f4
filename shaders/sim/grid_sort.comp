#version 450
// Pass 4. One thread per bucket sorts its particle ids ascending (insertion sort: buckets hold a
// handful of particles; there is no cap) and writes the bucket-ordered copies of position, body,
// velocity and inverse mass that the contact gather reads. After this pass the whole grid is a
// pure function of the particle positions: the step is deterministic.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START(readonly)
CELL_PARTICLES(coherent)
PARTICLE_POSITION(readonly)
PARTICLE_VELOCITY(readonly)
PARTICLE_BODY(readonly)
PARTICLE_LOCAL(readonly)
SORTED_POSITION(writeonly)
SORTED_VELOCITY(writeonly)

void main() {
  uint bucket = threadIndex();
  if (bucket >= counts2.y) return;
  uint begin = cellStart[bucket];
  uint end = cellStart[bucket + 1u];
  for (uint s = begin + 1u; s < end; ++s) {
    uint id = cellParticles[s];
    uint t = s;
    while (t > begin && cellParticles[t - 1u] > id) {
      cellParticles[t] = cellParticles[t - 1u];
      --t;
    }
    cellParticles[t] = id;
  }
  for (uint s = begin; s < end; ++s) {
    uint id = cellParticles[s];
    sortedPosition[s] = vec4(particlePosition[id].xyz, uintBitsToFloat(particleBody[id]));
    sortedVelocity[s] = vec4(particleVelocity[id].xyz, particleLocal[id].w);
  }
}
