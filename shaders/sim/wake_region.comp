#version 450
// World::wake (SLEEPING): every sleeping granule whose centre lies in the box [lo, hi] wakes, and
// every sleeping large body that reaches into it (its centre within its bounding radius of it).
// Its calm count, and its particles' copies, become 1: awake, but not moving, so that its
// sleeping neighbours only check their balance against it rather than wake with it
// (layout.glsl, "Sleep"). Not a pass of every substep.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(readonly)
BODY_ANGULAR_VELOCITY(readonly)
BODY_VELOCITY(coherent)
BODY_INFO(readonly)
PARTICLE_SPIN(coherent)

layout(location = 0) uniform vec3 lo;
layout(location = 1) uniform vec3 hi;

void main() {
  uint b = threadIndex();
  if (b >= params.bodyCount) return;
  uvec4 info = bodyInfo[b];
  if ((info.z & BODY_ALIVE) == 0u || floatBitsToUint(bodyVelocity[b].w) < params.sleepSubsteps)
    return;
  vec3 p = bodyPosition[b].xyz;
  float reach = (info.z & BODY_LARGE) != 0u ? bodyAngularVelocity[b].w : 0.0;
  if (any(lessThan(p, lo - reach)) || any(greaterThan(p, hi + reach))) return;
  bodyVelocity[b].w = uintBitsToFloat(1u);
  for (uint k = info.x; k < info.x + info.y; ++k) particleSpin[k].w = uintBitsToFloat(1u);
}
