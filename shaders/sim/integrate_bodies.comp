#version 450
// Pass 4. Granules: one thread per body sums its particles' forces and torques (paper eq. 2, 3):
// r x F about the centre for each particle's force, plus, under ContactLaw::HertzMindlin, the
// torque of friction at the contact points; in particle order (fixed, so deterministic). Then it
// integrates (common/rigid_motion.glsl), under HertzMindlin counts the contacts its particles'
// slots hold per partner when they changed (common/contact_pairs.glsl), and writes its
// particles' state for the next substep (common/particle_state.glsl). Bodies flagged BODY_LARGE
// (every body that is not a granule) are left to pass 4b. Under SLEEPING (layout.glsl, "Sleep")
// it runs over the granules collect_active.comp listed: a sleeping one whose partners all sleep
// returns at once; one that something awake touches counts its pairs (its contacts were
// computed) and wakes if a partner moves, its contacts changed, or the force or torque on it
// departs from balance by more than the wake acceleration; else it stays put.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(coherent)
BODY_ORIENTATION(coherent)
BODY_VELOCITY(coherent)
BODY_ANGULAR_VELOCITY(coherent)
BODY_INERTIA(readonly)
BODY_INFO(coherent)
PARTICLE_LOCAL_TEXTURE
PARTICLE_FORCE_TEXTURE
LIST_ORIGIN_TEXTURE
PARTICLE_POSITION(writeonly)
PARTICLE_VELOCITY(writeonly)
SINKS(readonly)
COUNTERS(coherent)
#ifdef SLEEPING
ACTIVE_BODIES(readonly)
LIST_ORIGIN(writeonly)
BODY_GRID_BUILD(writeonly)
#endif
#ifndef PAPER_LAW
PARTICLE_SPIN(writeonly)
PARTICLE_TORQUE_TEXTURE
PARTICLE_BODY_TEXTURE
CONTACT_SLOTS_0_TEXTURE
CONTACT_SLOTS_1_TEXTURE
CONTACT_SLOTS_2_TEXTURE
CONTACT_PAIRS(writeonly)
#include "common/contact_pairs.glsl"
#endif

#include "common/rigid_motion.glsl"
#include "common/particle_state.glsl"

// The particles of a granule (tetrahedronTemplate).
#define GRANULE_PARTICLES 4u

#ifndef PAPER_LAW
// Adds to each slot of group a the slots of group b that name its partner, and to each slot of
// b those of a.
void countBlock(uvec4 a, uvec4 b, inout uvec4 countsA, inout uvec4 countsB) {
  for (uint c = 0u; c < 4u; ++c) {
    uvec4 same = uvec4(equal(b, uvec4(a[c])));
    countsA[c] += same.x + same.y + same.z + same.w;
    countsB += same;
  }
}

// The same within one group.
void countOwnBlock(uvec4 a, inout uvec4 countsA) {
  for (uint c = 0u; c < 4u; ++c) {
    uvec4 same = uvec4(equal(a, uvec4(a[c])));
    countsA[c] += same.x + same.y + same.z + same.w;
  }
}

// Every slot of the granule against every other, a group of four against a group of four. Slots
// fill from the first on, so a particle's group g > 0 is in use only when its group g - 1 is
// full; the blocks of groups not in use are skipped (on a CPU a branch no lane takes costs
// nothing, on a GPU it is a uniform branch for most warps). All indices are constant once
// unrolled.
void countPairs(uint first) {
  uvec4 partners[GRANULE_PARTICLES * CONTACT_SLOT_GROUPS];
  uvec4 counts[GRANULE_PARTICLES * CONTACT_SLOT_GROUPS];
  bool inUse[GRANULE_PARTICLES * CONTACT_SLOT_GROUPS];
  for (uint p = 0u; p < GRANULE_PARTICLES; ++p) {
    for (uint g = 0u; g < CONTACT_SLOT_GROUPS; ++g) {
      uint i = p * CONTACT_SLOT_GROUPS + g;
      inUse[i] = g == 0u || slotsInUse(partners[i - 1u]) == 4u;
      partners[i] = uvec4(PARTNER_NONE);
      if (inUse[i]) partners[i] = slotPartners(first + p, g);
      counts[i] = uvec4(0u);
    }
  }
  for (uint i = 0u; i < GRANULE_PARTICLES * CONTACT_SLOT_GROUPS; ++i) {
    if (inUse[i]) {
      countOwnBlock(partners[i], counts[i]);
      for (uint j = 0u; j < GRANULE_PARTICLES * CONTACT_SLOT_GROUPS; ++j) {
        if (j < i && inUse[j]) countBlock(partners[i], partners[j], counts[i], counts[j]);
      }
    }
  }
  for (uint p = 0u; p < GRANULE_PARTICLES; ++p) {
    uvec4 slotCounts = uvec4(0u);
    for (uint g = 0u; g < CONTACT_SLOT_GROUPS; ++g) {
      uint i = p * CONTACT_SLOT_GROUPS + g;
      slotCounts[g] = packPairs(partners[i], counts[i]);
      slotCounts.w += slotsInUse(partners[i]);
    }
    contactPairs[first + p] = slotCounts;
  }
}
#endif

void main() {
#ifdef SLEEPING
  // The active granules only (collect_active.comp).
  uint t = threadIndex();
  if (t >= activeListLength(ACTIVE_PASS_BODIES)) return;
  uint b = activeBodies[t];
#else
  uint b = threadIndex();
  if (b >= params.bodyCount) return;
#endif
  uvec4 info = bodyInfo[b];
  if ((info.z & BODY_ALIVE) == 0u) return;
  // Bodies that are not granules are summed and moved by integrate_large_bodies.comp.
  if ((info.z & BODY_LARGE) != 0u) return;
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  if (motion == MOTION_STATIC) return;
  uint previousCalm = 0u;
  uint neighbourCalm = CALM_UNBOUNDED;
#ifdef SLEEPING
  previousCalm = floatBitsToUint(bodyVelocity[b].w);
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    neighbourCalm =
        min(neighbourCalm, floatBitsToUint(texelFetch(particleForceTexture, int(info.x + k)).w));
  }
  bool asleep = previousCalm >= params.sleepSubsteps;
  if (asleep && neighbourCalm >= params.sleepSubsteps) return;
#endif
  // A granule's particles: its offsets turned by the orientation the contacts saw.
  vec4 q = bodyOrientation[b];
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
  if (recount) countPairs(info.x);
#endif
#ifdef SLEEPING
  if (asleep) {
    float mass = bodyInertia[b].w;
    vec3 unbalanced = force / mass + params.gravity;
    float torqueLimit = mass * bodyAngularVelocity[b].w * params.wakeAcceleration;
    bool wake = neighbourCalm == 0u ||
                dot(unbalanced, unbalanced) > params.wakeAcceleration * params.wakeAcceleration ||
                dot(torque, torque) > torqueLimit * torqueLimit;
    if (!wake) return;
    previousCalm = 0u;
  }
#endif
  uint calmLimit = motion == MOTION_DYNAMIC ? params.sleepSubsteps : params.sleepSubsteps - 1u;
  BodyMotion moved =
      integrateBody(b, info, force, torque, previousCalm, neighbourCalm, calmLimit);
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
