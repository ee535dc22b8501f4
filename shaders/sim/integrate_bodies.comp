#version 450
// Pass 4. Granules: one thread per body sums its particles' forces and torques (paper eq. 2, 3):
// r x F about the centre for each particle's force, plus, under ContactLaw::HertzMindlin, the
// torque of friction at the contact points; in particle order (fixed, so deterministic). Then it
// integrates (common/rigid_motion.glsl), under HertzMindlin counts the contacts its particles'
// slots hold per partner (common/contact_pairs.glsl), and writes its particles' state for the
// next substep (common/particle_state.glsl). Bodies flagged BODY_LARGE (every body that is not a
// granule) are left to pass 4b.
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
// Every slot of the granule against every other, four at a time (all indices constant once
// unrolled).
void countPairs(uint first) {
  uvec4 partners[GRANULE_PARTICLES * CONTACT_SLOT_GROUPS];
  for (uint g = 0u; g < GRANULE_PARTICLES * CONTACT_SLOT_GROUPS; ++g) {
    partners[g] = slotPartners(first + g / CONTACT_SLOT_GROUPS, g % CONTACT_SLOT_GROUPS);
  }
  for (uint p = 0u; p < GRANULE_PARTICLES; ++p) {
    uvec4 slotCounts = uvec4(0u);
    for (uint group = 0u; group < CONTACT_SLOT_GROUPS; ++group) {
      uvec4 mine = partners[p * CONTACT_SLOT_GROUPS + group];
      slotCounts.w += slotsInUse(mine);
      uvec4 counts = uvec4(0u);
      for (uint c = 0u; c < 4u; ++c) {
        uvec4 same = uvec4(0u);
        for (uint g = 0u; g < GRANULE_PARTICLES * CONTACT_SLOT_GROUPS; ++g) {
          same += uvec4(equal(partners[g], uvec4(mine[c])));
        }
        counts[c] = same.x + same.y + same.z + same.w;
      }
      slotCounts[group] = packPairs(mine, counts);
    }
    contactPairs[first + p] = slotCounts;
  }
}
#endif

void main() {
  uint b = threadIndex();
  if (b >= counts.y) return;
  uvec4 info = bodyInfo[b];
  if ((info.z & BODY_ALIVE) == 0u) return;
  // Bodies that are not granules are summed and moved by integrate_large_bodies.comp.
  if ((info.z & BODY_LARGE) != 0u) return;
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  if (motion == MOTION_STATIC) return;
  // A granule's particles: its offsets turned by the orientation the contacts saw.
  vec4 q = bodyOrientation[b];
  vec4 local[GRANULE_PARTICLES];
  vec3 force = vec3(0.0);
  vec3 torque = vec3(0.0);
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    local[k] = texelFetch(particleLocalTexture, int(info.x + k));
    vec3 f = texelFetch(particleForceTexture, int(info.x + k)).xyz;
    force += f;
    torque += cross(quatRotate(q, local[k].xyz), f);
#ifndef PAPER_LAW
    torque += texelFetch(particleTorqueTexture, int(info.x + k)).xyz;
#endif
  }
  BodyMotion moved = integrateBody(b, info, force, torque);
#ifndef PAPER_LAW
  countPairs(info.x);
#endif
  if (!moved.alive) return;
  for (uint k = 0u; k < GRANULE_PARTICLES; ++k) {
    storeParticle(info.x + k, local[k], b, moved.position, moved.orientation, moved.velocity,
                  moved.spin);
  }
}
