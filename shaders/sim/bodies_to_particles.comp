#version 450
// Pass 1. Bodies -> particles (paper eq. 7, 8): world position and velocity of every particle
// from its body's pose, velocity and spin, and the particle's hash bucket, counted with an integer
// atomic (exact, order independent).
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(readonly)
BODY_ORIENTATION(readonly)
BODY_VELOCITY(readonly)
BODY_ANGULAR_VELOCITY(readonly)
BODY_INFO(readonly)
PARTICLE_LOCAL(readonly)
PARTICLE_BODY(readonly)
PARTICLE_POSITION(writeonly)
PARTICLE_VELOCITY(writeonly)
PARTICLE_CELL(writeonly)
CELL_COUNT(coherent)

void main() {
  uint i = threadIndex();
  if (i >= counts.x) return;
  uint body = particleBody[i];
  if ((bodyInfo[body].z & BODY_ALIVE) == 0u) {
    particleCell[i] = INVALID_CELL;
    return;
  }
  vec3 offset = quatRotate(bodyOrientation[body], particleLocal[i].xyz);
  vec3 position = bodyPosition[body].xyz + offset;
  vec3 velocity = bodyVelocity[body].xyz + cross(bodyAngularVelocity[body].xyz, offset);
  particlePosition[i] = vec4(position, 0.0);
  particleVelocity[i] = vec4(velocity, 0.0);
  uint bucket = bucketOf(cellOf(position));
  particleCell[i] = bucket;
  atomicAdd(cellCount[bucket], 1u);
}
