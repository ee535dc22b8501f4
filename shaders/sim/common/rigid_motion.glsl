// One substep of rigid-body motion, shared by integrate_bodies.comp (granules, a thread each) and
// integrate_large_bodies.comp (every other body, a workgroup each): semi-implicit Euler, the
// velocity first, then the position with the new velocity; the spin in the principal frame with
// the gyroscopic term (paper eq. 4, 6), and the orientation by the quaternion update (eq. 5),
// renormalised. Applies the speed guard and, to granules, the sinks. The includer declares
// BODY_POSITION, BODY_ORIENTATION, BODY_VELOCITY, BODY_ANGULAR_VELOCITY, BODY_INFO (coherent),
// SINKS (readonly) and COUNTERS, and includes quaternion.glsl.

// A body's state as stored before its substep, read by the includer (integrate_bodies.comp
// through the buffer textures: a load from a storage buffer at an index that differs between
// lanes runs lane by lane on llvmpipe, a texel fetch is one gather).
struct StoredBody {
  vec4 position;     // w: inverse mass
  vec4 orientation;
  vec4 velocity;     // w: calm count (uint bits)
  vec4 spin;         // angular velocity; w as integrate keeps it
  vec4 inertia;      // principal moments of inertia; w: mass
};

// A body's state after its substep, for the particles that follow it.
struct BodyMotion {
  vec3 position;
  vec4 orientation;
  vec3 velocity;
  vec3 spin;
  bool alive;
  uint calm;  // its calm count (layout.glsl, "Sleep"; 0 without SLEEPING)
};

// The most a movable body's calm count reaches (layout.glsl, "Sleep"): params.sleepSubsteps,
// asleep, for a dynamic body, and for a kinematic one set exactly at rest (sleep stops a body
// dead, which must then change nothing); one short of it for a kinematic body that moves.
uint calmLimit(uint motion, StoredBody stored) {
  bool rests =
      all(equal(stored.velocity.xyz, vec3(0.0))) && all(equal(stored.spin.xyz, vec3(0.0)));
  return motion == MOTION_DYNAMIC || rests ? params.sleepSubsteps : params.sleepSubsteps - 1u;
}

#ifdef SLEEPING
// Whether a sleeping body that something awake touched wakes: a dynamic one when a partner
// moves or its contacts changed (`neighbourCalm` 0), or the force or torque on it departs from
// balance by more than the wake acceleration; a kinematic one never (the CPU wakes it by setting
// it).
bool wakesWhenTouched(uint motion, StoredBody stored, vec3 force, vec3 torque,
                      uint neighbourCalm) {
  if (motion != MOTION_DYNAMIC) return false;
  float mass = stored.inertia.w;
  vec3 unbalanced = force / mass + params.gravity;
  float torqueLimit = mass * stored.spin.w * params.wakeAcceleration;
  return neighbourCalm == 0u ||
         dot(unbalanced, unbalanced) > params.wakeAcceleration * params.wakeAcceleration ||
         dot(torque, torque) > torqueLimit * torqueLimit;
}
#endif

// Advances body `b` (alive, not static) by one substep under the sum of its particles' contact
// forces `force` and their torque about its centre of mass `torque`; kinematic bodies keep their
// velocities and only move. A granule that a sink takes asks for a list build (its particles
// leave the lists). Under SLEEPING the calm count follows from the body's count `previousCalm`,
// the smallest count of the bodies it touches `neighbourCalm` and its limit `calmLimit`; a body
// that reaches params.sleepSubsteps stops dead, so that what touches it sees it at rest.
BodyMotion integrateBody(uint b, uvec4 info, StoredBody stored, vec3 force, vec3 torque,
                         uint previousCalm, uint neighbourCalm, uint calmLimit) {
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  float dt = params.dt;
  vec4 position = stored.position;
  vec4 q = stored.orientation;
  vec3 v = stored.velocity.xyz;
  vec4 spin = stored.spin;
  vec3 omega = spin.xyz;

  if (motion == MOTION_DYNAMIC) {
    v += dt * (force * position.w + params.gravity);
    // Euler's equations in the principal frame: I w' = T - w x (I w).
    vec3 inertia = stored.inertia.xyz;
    vec3 omegaLocal = quatRotateInverse(q, omega);
    vec3 torqueLocal = quatRotateInverse(q, torque);
    omegaLocal += dt * (torqueLocal - cross(omegaLocal, inertia * omegaLocal)) / inertia;
    omega = quatRotate(q, omegaLocal);

    // Speed guard (paper: CFL velocity clamp), counted per body.
    float maxSpeed = params.maxSpeed;
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

  uint calm = 0u;
#ifdef SLEEPING
  if (dot(v, v) < params.sleepLinearSpeed * params.sleepLinearSpeed &&
      dot(omega, omega) < params.sleepAngularSpeed * params.sleepAngularSpeed) {
    calm = min(min(previousCalm + 1u, min(neighbourCalm, calmLimit) + params.sleepNeighbourLead),
               calmLimit);
  }
  if (calm >= params.sleepSubsteps) {
    v = vec3(0.0);
    omega = vec3(0.0);
  }
#endif

  if ((info.z & BODY_GRANULE) != 0u) {
    for (uint k = 0u; k < params.sinkCount; ++k) {
      if (all(greaterThanEqual(position.xyz, sinks[k].lo.xyz)) &&
          all(lessThanEqual(position.xyz, sinks[k].hi.xyz))) {
        info.z &= ~BODY_ALIVE;
        atomicAdd(counters[COUNTER_KILLED], 1u);
        counters[COUNTER_LIST_REQUESTED] = LIST_REQUEST_MOVED;
        v = vec3(0.0);
        omega = vec3(0.0);
        break;
      }
    }
  }

  bodyPosition[b] = position;
  bodyOrientation[b] = q;
  bodyVelocity[b] = vec4(v, uintBitsToFloat(calm));
  bodyAngularVelocity[b] = vec4(omega, spin.w);
  bodyInfo[b] = info;
  return BodyMotion(position.xyz, q, v, omega, (info.z & BODY_ALIVE) != 0u, calm);
}
