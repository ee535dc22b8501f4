#version 450
// Pass 4b. Every body that is not a granule (mesh-sampled bodies, bodies coupled to Bullet, a
// viewer's pusher), whatever its particle count: one workgroup per body. Each thread sums a
// strided share of the particles' forces and torques r x F in particle order, then a tree in
// shared memory adds the shares in a fixed order, so the sum is the same on every run. Thread 0
// adds the result to the body's read-back sums (World::takeBodyForces) and integrates the body
// (common/rigid_motion.glsl); then the group writes the particles' state for the next substep
// (common/particle_state.glsl). Kinematic bodies are summed too: their sand force is what a bridge
// hands back to the engine that moves them. Under ContactLaw::HertzMindlin the torques include
// friction at the contact points, and the group counts its slots per partner in a table in
// shared memory (common/contact_pairs.glsl): integer atomics, so the counts are exact and the
// same on every run, whatever order the threads insert in. Under SLEEPING (layout.glsl, "Sleep")
// it runs over the large bodies collect_active.comp listed, as integrate_bodies.comp does over
// the granules: a sleeping one whose partners all sleep returns at once, one that something
// awake touches is summed (and its pair counts taken) and wakes as a granule does unless it is
// kinematic; so a body at rest costs nothing while the sand around it sleeps.
#include "common/layout.glsl"
#include "common/quaternion.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION(coherent)
BODY_ORIENTATION(coherent)
BODY_VELOCITY(coherent)
BODY_ANGULAR_VELOCITY(coherent)
BODY_INERTIA_TEXTURE
BODY_INFO(coherent)
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
LARGE_BODIES(readonly)
#ifdef SLEEPING
ACTIVE_LARGE_BODIES(readonly)
#endif
LARGE_BODY_FORCES(coherent)
#if !defined(PAPER_LAW) && defined(SLEEPING)
PARTICLE_SPIN(writeonly)
#endif
#ifndef PAPER_LAW
PARTICLE_TORQUE(readonly)
PARTICLE_BODY_TEXTURE
CONTACT_SLOTS_0_TEXTURE
CONTACT_SLOTS_1_TEXTURE
CONTACT_SLOTS_2_TEXTURE
CONTACT_PAIRS(writeonly)
#include "common/contact_pairs.glsl"
#endif

#include "common/rigid_motion.glsl"
#include "common/particle_state.glsl"

shared vec3 shareForce[WORKGROUP_SIZE];
shared vec3 shareTorque[WORKGROUP_SIZE];
#ifdef SLEEPING
shared uint shareCalm[WORKGROUP_SIZE];  // the smallest neighbours' calm (particleForce.w)
#endif
// The body after thread 0 moved it (w of the position: 1 when it moved and is alive, so that the
// group writes its particles).
shared vec4 movedPosition;
shared vec4 movedOrientation;
shared vec3 movedVelocity;
shared vec3 movedSpin;
shared uint movedCalm;

#ifndef PAPER_LAW
// Open addressing, partner -> number of the body's slots naming it. A body with more distinct
// partners than entries leaves the rest at n = 1 (the bodies' masses unshared).
#define PAIR_TABLE 1024u
shared uint pairPartner[PAIR_TABLE];
shared uint pairCount[PAIR_TABLE];

uint pairHash(uint partner) {
  return (partner * 0x9e3779b1u) >> 22u;  // the top 10 bits: PAIR_TABLE entries
}

void insertPartner(uint partner) {
  uint h = pairHash(partner);
  for (uint probe = 0u; probe < PAIR_TABLE; ++probe) {
    uint found = atomicCompSwap(pairPartner[h], PARTNER_NONE, partner);
    if (found == PARTNER_NONE || found == partner) {
      atomicAdd(pairCount[h], 1u);
      return;
    }
    h = (h + 1u) % PAIR_TABLE;
  }
}

uint countOf(uint partner) {
  uint h = pairHash(partner);
  for (uint probe = 0u; probe < PAIR_TABLE; ++probe) {
    uint found = pairPartner[h];
    if (found == partner) return pairCount[h];
    if (found == PARTNER_NONE) break;
    h = (h + 1u) % PAIR_TABLE;
  }
  return 1u;
}

// A particle's slots are filled from the first on, so a free first slot means no contacts: most
// particles of a large body touch nothing and cost one fetch.
bool hasContacts(uint particle) {
  return slotPartner(particle, 0u) != PARTNER_NONE;
}

void countPairs(uint first, uint count, uint t) {
  for (uint e = t; e < PAIR_TABLE; e += WORKGROUP_SIZE) {
    pairPartner[e] = PARTNER_NONE;
    pairCount[e] = 0u;
  }
  memoryBarrierShared();
  barrier();
  for (uint k = first + t; k < first + count; k += WORKGROUP_SIZE) {
    if (!hasContacts(k)) continue;
    for (uint slot = 0u; slot < uint(CONTACT_SLOTS); ++slot) {
      uint partner = slotPartner(k, slot);
      if (partner == PARTNER_NONE) break;
      insertPartner(partner);
    }
  }
  memoryBarrierShared();
  barrier();
  // Particles without contacts keep stale counts: only a slot that matches a contact is read.
  for (uint k = first + t; k < first + count; k += WORKGROUP_SIZE) {
    if (!hasContacts(k)) continue;
    uvec4 slotCounts = uvec4(0u);
    for (uint group = 0u; group < CONTACT_SLOT_GROUPS; ++group) {
      uvec4 partners = slotPartners(k, group);
      uvec4 counts = uvec4(countOf(partners.x), countOf(partners.y), countOf(partners.z),
                           countOf(partners.w));
      slotCounts[group] = packPairs(partners, counts);
      slotCounts.w += slotsInUse(partners);
    }
    contactPairs[k] = slotCounts;
  }
}
#endif

void main() {
#ifdef SLEEPING
  if (gl_WorkGroupID.x >= activeListLength(ACTIVE_PASS_LARGE)) return;
  uint entry = activeLargeBodies[gl_WorkGroupID.x];
#else
  uint entry = gl_WorkGroupID.x;
#endif
  uint b = largeBodies[entry];
  uvec4 info = bodyInfo[b];
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  // The same for every thread of the group, so no barrier below is skipped by some only.
  if ((info.z & BODY_ALIVE) == 0u || motion == MOTION_STATIC) return;

  uint t = gl_LocalInvocationID.x;
  vec4 q = bodyOrientation[b];
  vec3 force = vec3(0.0);
  vec3 torque = vec3(0.0);
  uint neighbourCalm = CALM_UNBOUNDED;
  for (uint k = info.x + t; k < info.x + info.y; k += WORKGROUP_SIZE) {
    vec4 onParticle = texelFetch(particleForceTexture, int(k));
    vec3 f = onParticle.xyz;
    force += f;
#ifdef SLEEPING
    neighbourCalm = min(neighbourCalm, floatBitsToUint(onParticle.w));
#endif
    torque += cross(quatRotate(q, texelFetch(particleLocalTexture, int(k)).xyz), f);
#ifndef PAPER_LAW
    torque += particleTorque[k].xyz;
#endif
  }
  shareForce[t] = force;
  shareTorque[t] = torque;
#ifdef SLEEPING
  shareCalm[t] = neighbourCalm;
  // Read before thread 0 writes it, below.
  bool asleep = floatBitsToUint(bodyVelocity[b].w) >= params.sleepSubsteps;
#endif
  memoryBarrierShared();
  barrier();
  for (uint stride = WORKGROUP_SIZE / 2u; stride > 0u; stride >>= 1u) {
    if (t < stride) {
      shareForce[t] += shareForce[t + stride];
      shareTorque[t] += shareTorque[t + stride];
#ifdef SLEEPING
      shareCalm[t] = min(shareCalm[t], shareCalm[t + stride]);
#endif
    }
    memoryBarrierShared();
    barrier();
  }
#ifdef SLEEPING
  neighbourCalm = shareCalm[0];
  // Nothing awake touches it now: it neither moves nor gains a force (the same in every thread).
  if (asleep && neighbourCalm >= params.sleepSubsteps) return;
#endif
#ifndef PAPER_LAW
  countPairs(info.x, info.y, t);
#endif
  if (t == 0u) {
    force = shareForce[0];
    torque = shareTorque[0];
    largeBodyForces[2u * entry] += vec4(force, 1.0);
    largeBodyForces[2u * entry + 1u] += vec4(torque, 0.0);
    StoredBody stored =
        StoredBody(bodyPosition[b], bodyOrientation[b], bodyVelocity[b], bodyAngularVelocity[b],
                   texelFetch(bodyInertiaTexture, int(b)));
    uint previousCalm = floatBitsToUint(stored.velocity.w);
    bool moves = true;
#ifdef SLEEPING
    if (asleep) {
      moves = wakesWhenTouched(motion, stored, force, torque, neighbourCalm);
      previousCalm = 0u;
    }
#endif
    movedPosition.w = 0.0;
    if (moves) {
      BodyMotion moved = integrateBody(b, info, stored, force, torque, previousCalm,
                                       neighbourCalm, calmLimit(motion, stored));
      movedPosition = vec4(moved.position, moved.alive ? 1.0 : 0.0);
      movedOrientation = moved.orientation;
      movedVelocity = moved.velocity;
      movedSpin = moved.spin;
      movedCalm = moved.calm;
    }
  }
  memoryBarrierShared();
  barrier();
  if (movedPosition.w == 0.0) return;
  for (uint k = info.x + t; k < info.x + info.y; k += WORKGROUP_SIZE) {
    storeParticle(k, texelFetch(particleLocalTexture, int(k)), b, movedPosition.xyz,
                  movedOrientation, movedVelocity, movedSpin, movedCalm);
  }
}
