#version 450
// Pass 6. Bodies: one thread per body sums its particles' forces and torques r x F (paper eq. 2,
// 3) in particle order (fixed, so deterministic), then integrates with semi-implicit Euler: the
// velocity first, then the position with the new velocity; the spin in the principal frame with
// the gyroscopic term (eq. 4, 6), and the orientation by the quaternion update (eq. 5),
// renormalised. Applies the speed guard and the sinks.
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

void main() {
  uint b = threadIndex();
  if (b >= counts.y) return;
  uvec4 info = bodyInfo[b];
  if ((info.z & BODY_ALIVE) == 0u) return;
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  if (motion == MOTION_STATIC) return;
  float dt = gravityDt.w;
  vec4 position = bodyPosition[b];
  vec4 q = bodyOrientation[b];
  vec3 v = bodyVelocity[b].xyz;
  vec4 spin = bodyAngularVelocity[b];
  vec3 omega = spin.xyz;

  if (motion == MOTION_DYNAMIC) {
    vec3 force = vec3(0.0);
    vec3 torque = vec3(0.0);
    for (uint k = info.x; k < info.x + info.y; ++k) {
      vec3 f = particleForce[k].xyz;
      force += f;
      torque += cross(particlePosition[k].xyz - position.xyz, f);
    }
    v += dt * (force * position.w + gravityDt.xyz);
    // Euler's equations in the principal frame: I w' = T - w x (I w).
    vec3 inertia = bodyInertia[b].xyz;
    vec3 omegaLocal = quatRotateInverse(q, omega);
    vec3 torqueLocal = quatRotateInverse(q, torque);
    omegaLocal += dt * (torqueLocal - cross(omegaLocal, inertia * omegaLocal)) / inertia;
    omega = quatRotate(q, omegaLocal);

    // Speed guard (paper: CFL velocity clamp), counted per body.
    float maxSpeed = wallContact.y;
    float speed = length(v);
    if (speed > maxSpeed) {
      v *= maxSpeed / speed;
      info.w += 1u;
    }
    float rimSpeed = length(omega) * spin.w;
    if (rimSpeed > maxSpeed) {
      omega *= maxSpeed / rimSpeed;
      info.w += 1u;
    }
  }

  position.xyz += dt * v;
  q += 0.5 * dt * quatMultiply(vec4(omega, 0.0), q);
  q = normalize(q);

  if ((info.z & BODY_GRANULE) != 0u) {
    for (uint k = 0u; k < counts2.x; ++k) {
      if (all(greaterThanEqual(position.xyz, sinks[k].lo.xyz)) &&
          all(lessThanEqual(position.xyz, sinks[k].hi.xyz))) {
        info.z &= ~BODY_ALIVE;
        atomicAdd(counters[COUNTER_KILLED], 1u);
        v = vec3(0.0);
        omega = vec3(0.0);
        break;
      }
    }
  }

  bodyPosition[b] = position;
  bodyOrientation[b] = q;
  bodyVelocity[b] = vec4(v, 0.0);
  bodyAngularVelocity[b] = vec4(omega, spin.w);
  bodyInfo[b] = info;
}
