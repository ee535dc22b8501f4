#version 450
// Pass 4b. One thread per bucket-ordered slot writes the copies of position, body, velocity and
// inverse mass (and, for ContactLaw::HertzMindlin, the body's spin and the particle's id) that
// the contact gather reads, so that particles near in space are near in memory.
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
#ifndef PAPER_LAW
BODY_ANGULAR_VELOCITY_TEXTURE
SORTED_SPIN(writeonly)
#endif

void main() {
  uint s = threadIndex();
  // Particles of dead bodies have no slot: the table's total is the number of slots.
  if (s >= texelFetch(cellStartTexture, int(counts2.y)).x) return;
  uint id = texelFetch(cellParticlesTexture, int(s)).x;
  uint body = texelFetch(particleBodyTexture, int(id)).x;
  sortedPosition[s] = vec4(texelFetch(particlePositionTexture, int(id)).xyz, uintBitsToFloat(body));
  sortedVelocity[s] = vec4(texelFetch(particleVelocityTexture, int(id)).xyz,
                           texelFetch(particleLocalTexture, int(id)).w);
#ifndef PAPER_LAW
  sortedSpin[s] = vec4(texelFetch(bodyAngularVelocityTexture, int(body)).xyz, uintBitsToFloat(id));
#endif
}
