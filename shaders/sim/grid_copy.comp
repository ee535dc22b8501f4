#version 450
// Pass 4b. One thread per bucket-ordered slot writes the copies of position, body, velocity and
// inverse mass that the contact gather reads, so that particles near in space are near in memory.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_POSITION_TEXTURE
PARTICLE_VELOCITY_TEXTURE
PARTICLE_BODY_TEXTURE
PARTICLE_LOCAL_TEXTURE
SORTED_POSITION(writeonly)
SORTED_VELOCITY(writeonly)

void main() {
  uint s = threadIndex();
  // Particles of dead bodies have no slot: the table's total is the number of slots.
  if (s >= texelFetch(cellStartTexture, int(counts2.y)).x) return;
  int id = int(texelFetch(cellParticlesTexture, int(s)).x);
  sortedPosition[s] = vec4(texelFetch(particlePositionTexture, id).xyz,
                           uintBitsToFloat(texelFetch(particleBodyTexture, id).x));
  sortedVelocity[s] = vec4(texelFetch(particleVelocityTexture, id).xyz,
                           texelFetch(particleLocalTexture, id).w);
}
