#version 450
// Pass 6. Granules: one thread per body sums its particles' forces and torques r x F (paper eq.
// 2, 3) in particle order (fixed, so deterministic), then integrates (common/rigid_motion.glsl).
// Bodies flagged BODY_LARGE (every body that is not a granule) are left to pass 6b.
#include "common/layout.glsl"
#include "common/quaternion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(coherent)
BODY_ORIENTATION(coherent)
BODY_VELOCITY(coherent)
BODY_ANGULAR_VELOCITY(coherent)
BODY_INERTIA(readonly)
BODY_INFO(coherent)
PARTICLE_POSITION_TEXTURE
PARTICLE_FORCE_TEXTURE
SINKS(readonly)
COUNTERS(coherent)

#include "common/rigid_motion.glsl"

void main() {
  uint b = threadIndex();
  if (b >= counts.y) return;
  uvec4 info = bodyInfo[b];
  if ((info.z & BODY_ALIVE) == 0u) return;
  // Bodies that are not granules are summed and moved by integrate_large_bodies.comp.
  if ((info.z & BODY_LARGE) != 0u) return;
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  if (motion == MOTION_STATIC) return;
  vec3 centre = bodyPosition[b].xyz;
  vec3 force = vec3(0.0);
  vec3 torque = vec3(0.0);
  if (motion == MOTION_DYNAMIC) {
    for (uint k = info.x; k < info.x + info.y; ++k) {
      vec3 f = texelFetch(particleForceTexture, int(k)).xyz;
      force += f;
      torque += cross(texelFetch(particlePositionTexture, int(k)).xyz - centre, f);
    }
  }
  integrateBody(b, info, force, torque);
}
