#version 450
// Pass 1. Bodies -> particles (paper eq. 7, 8): world position and velocity of every particle
// from its body's pose, velocity and spin, and the particle's hash bucket, counted with an integer
// atomic (exact, order independent).
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION_TEXTURE
BODY_ORIENTATION_TEXTURE
BODY_VELOCITY_TEXTURE
BODY_ANGULAR_VELOCITY_TEXTURE
BODY_INFO_TEXTURE
PARTICLE_LOCAL_TEXTURE
PARTICLE_BODY_TEXTURE
PARTICLE_POSITION(writeonly)
PARTICLE_VELOCITY(writeonly)
PARTICLE_CELL(writeonly)
CELL_COUNT(coherent)

#include "common/particle_offset.glsl"

void main() {
  uint i = threadIndex();
  if (i >= counts.x) return;
  int body = int(texelFetch(particleBodyTexture, int(i)).x);
  if ((texelFetch(bodyInfoTexture, body).z & BODY_ALIVE) == 0u) {
    particleCell[i] = INVALID_CELL;
    return;
  }
  vec3 offset = particleOffset(body, int(i));
  vec3 position = texelFetch(bodyPositionTexture, body).xyz + offset;
  vec3 velocity = texelFetch(bodyVelocityTexture, body).xyz +
                  cross(texelFetch(bodyAngularVelocityTexture, body).xyz, offset);
  particlePosition[i] = vec4(position, 0.0);
  particleVelocity[i] = vec4(velocity, 0.0);
  uint bucket = bucketOf(cellOf(position));
  particleCell[i] = bucket;
  atomicAdd(cellCount[bucket], 1u);
}
