#version 450
// Pass 6b. Every body that is not a granule (mesh-sampled bodies, bodies coupled to Bullet, a
// viewer's pusher), whatever its particle count: one workgroup per body. Each thread sums a
// strided share of the particles' forces and torques r x F in particle order, then a tree in
// shared memory adds the shares in a fixed order, so the sum is the same on every run. Thread 0
// adds the result to the body's read-back sums (World::takeBodyForces) and integrates the body
// (common/rigid_motion.glsl). Kinematic bodies are summed too: their sand force is what a bridge
// hands back to the engine that moves them.
#include "common/layout.glsl"
#include "common/quaternion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(coherent)
BODY_ORIENTATION(coherent)
BODY_VELOCITY(coherent)
BODY_ANGULAR_VELOCITY(coherent)
BODY_INERTIA(readonly)
BODY_INFO(coherent)
PARTICLE_POSITION(readonly)
PARTICLE_FORCE(readonly)
SINKS(readonly)
COUNTERS(coherent)
LARGE_BODIES(readonly)
LARGE_BODY_FORCES(coherent)

#include "common/rigid_motion.glsl"

shared vec3 shareForce[WORKGROUP_SIZE];
shared vec3 shareTorque[WORKGROUP_SIZE];

void main() {
  uint entry = gl_WorkGroupID.x;
  uint b = largeBodies[entry];
  uvec4 info = bodyInfo[b];
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  // The same for every thread of the group, so no barrier below is skipped by some only.
  if ((info.z & BODY_ALIVE) == 0u || motion == MOTION_STATIC) return;

  uint t = gl_LocalInvocationID.x;
  vec3 centre = bodyPosition[b].xyz;
  vec3 force = vec3(0.0);
  vec3 torque = vec3(0.0);
  for (uint k = info.x + t; k < info.x + info.y; k += WORKGROUP_SIZE) {
    vec3 f = particleForce[k].xyz;
    force += f;
    torque += cross(particlePosition[k].xyz - centre, f);
  }
  shareForce[t] = force;
  shareTorque[t] = torque;
  memoryBarrierShared();
  barrier();
  for (uint stride = WORKGROUP_SIZE / 2u; stride > 0u; stride >>= 1u) {
    if (t < stride) {
      shareForce[t] += shareForce[t + stride];
      shareTorque[t] += shareTorque[t + stride];
    }
    memoryBarrierShared();
    barrier();
  }
  if (t != 0u) return;
  force = shareForce[0];
  torque = shareTorque[0];
  largeBodyForces[2u * entry] += vec4(force, 1.0);
  largeBodyForces[2u * entry + 1u] += vec4(torque, 0.0);
  integrateBody(b, info, force, torque);
}
