#version 450
// Pass 4. Granules: one thread per body sums its particles' forces and torques (paper eq. 2, 3):
// r x F about the centre for each particle's force, plus, under ContactLaw::HertzMindlin, the
// torque of friction at the contact points; in particle order (fixed, so deterministic). Then it
// integrates (common/rigid_motion.glsl), under HertzMindlin lists it for count_pairs.comp when
// its particles' contact slots changed, and writes its particles' state for the next substep
// (common/particle_state.glsl). Bodies flagged BODY_LARGE (every body that is not a granule) are
// left to pass 4b. Under SLEEPING (layout.glsl, "Sleep") it runs over the granules
// collect_active.comp listed: a sleeping one whose partners all sleep returns at once; one that
// something awake touches is listed for its pair counts as above (its contacts were computed)
// and wakes if common/rigid_motion.glsl says so (wakesWhenTouched); else it stays put.
#include "common/layout.glsl"
#include "common/quaternion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(coherent)
BODY_ORIENTATION(coherent)
BODY_VELOCITY(coherent)
BODY_ANGULAR_VELOCITY(coherent)
BODY_INFO(coherent)
BODY_POSITION_TEXTURE
BODY_ORIENTATION_TEXTURE
BODY_VELOCITY_TEXTURE
BODY_ANGULAR_VELOCITY_TEXTURE
BODY_INFO_TEXTURE
BODY_INERTIA_TEXTURE
PARTICLE_LOCAL_TEXTURE
PARTICLE_FORCE_TEXTURE
LIST_ORIGIN_TEXTURE
#ifndef SLEEPING
LIST_NEAR_TEXTURE
#endif
PARTICLE_POSITION(writeonly)
PARTICLE_VELOCITY(writeonly)
SINKS(readonly)
COUNTERS(coherent)
#ifdef SLEEPING
ACTIVE_BODIES(readonly)
LIST_ORIGIN(writeonly)
BODY_GRID_BUILD(writeonly)
#endif
#if !defined(PAPER_LAW) && defined(SLEEPING)
PARTICLE_SPIN(writeonly)
#endif
#ifndef PAPER_LAW
PARTICLE_TORQUE_TEXTURE
PAIRS_DUE(writeonly)
#endif

#include "common/rigid_motion.glsl"
#include "common/particle_state.glsl"
#include "common/list_decision.glsl"

// The particles of a granule (tetrahedronTemplate).
#define GRANULE_PARTICLES 4u

// Advances the granule of thread t, if it has one.
void advance(uint t) {
#ifdef SLEEPING
  // The active granules only (collect_active.comp).
  if (t >= activeListLength(ACTIVE_PASS_BODIES)) return;
  uint b = activeBodies[t];
#else
  uint b = t;
  if (b >= params.bodyCount) return;
#endif
  uvec4 info = texelFetch(bodyInfoTexture, int(b));
  if ((info.z & BODY_ALIVE) == 0u) return;
  // Bodies that are not granules are summed and moved by integrate_large_bodies.comp.
  if ((info.z & BODY_LARGE) != 0u) return;
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  if (motion == MOTION_STATIC) return;
  StoredBody stored = StoredBody(
      texelFetch(bodyPositionTexture, int(b)), texelFetch(bodyOrientationTexture, int(b)),
      texelFetch(bodyVelocityTexture, int(b)), texelFetch(bodyAngularVelocityTexture, int(b)),
      texelFetch(bodyInertiaTexture, int(b)));
  uint previousCalm = 0u;
  uint neighbourCalm = CALM_UNBOUNDED;
#ifdef SLEEPING
  previousCalm = floatBitsToUint(stored.velocity.w);
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    neighbourCalm =
        min(neighbourCalm, floatBitsToUint(texelFetch(particleForceTexture, int(info.x + k)).w));
  }
  bool asleep = previousCalm >= params.sleepSubsteps;
  if (asleep && neighbourCalm >= params.sleepSubsteps) return;
#endif
  // A granule's particles: its offsets turned by the orientation the contacts saw.
  vec4 q = stored.orientation;
  vec4 local[GRANULE_PARTICLES];
  vec3 force = vec3(0.0);
  vec3 torque = vec3(0.0);
  // The pair counts change only when some particle's slots did (or the bodies did: the CPU says).
  bool recount = counters[COUNTER_RECOUNT_PAIRS] != 0u;
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    local[k] = texelFetch(particleLocalTexture, int(info.x + k));
    vec3 f = texelFetch(particleForceTexture, int(info.x + k)).xyz;
    force += f;
    torque += cross(quatRotate(q, local[k].xyz), f);
#ifndef PAPER_LAW
    vec4 onParticle = texelFetch(particleTorqueTexture, int(info.x + k));
    torque += onParticle.xyz;
    recount = recount || onParticle.w != 0.0;
#endif
  }
#ifndef PAPER_LAW
  // Listed for count_pairs.comp, in any order: each granule's counts are its own.
  if (recount) pairsDue[appendToPass(ACTIVE_PASS_PAIRS)] = b;
#endif
#ifdef SLEEPING
  if (asleep) {
    if (!wakesWhenTouched(motion, stored, force, torque, neighbourCalm)) return;
    previousCalm = 0u;
  }
#endif
  BodyMotion moved = integrateBody(b, info, stored, force, torque, previousCalm, neighbourCalm,
                                   calmLimit(motion, stored));
  if (!moved.alive) {
#ifdef SLEEPING
    // A build the motion asks for passes over the dead (they are not active): they leave the
    // lists here.
    for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
      listOrigin[info.x + k].w = uintBitsToFloat(LIST_DEAD);
    }
    bodyGridBuild[b] = GRID_BUILD_DEAD;  // and the still grid's entries (common/grid.glsl)
#endif
    return;
  }
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    storeParticle(info.x + k, local[k], b, moved.position, moved.orientation, moved.velocity,
                  moved.spin, moved.calm);
  }
}

void main() {
  advance(threadIndex());
}
