#version 450
// The state hash of a recording (docs/recording.md), once per recorded frame: each body slot's
// stored bits (and its body's id, when that is not its index) are absorbed into two 32-bit lanes
// seeded with its index, and the lanes are summed
// over the slots. Integer sums do not depend on the order the threads ran in, so the hash is the
// same on every run; src/recording/state_hash.cpp computes the same function on the CPU. Under
// ContactLaw::HertzMindlin every particle's contact slots and pair counts (the history a
// contact carries across substeps) are absorbed the same way, seeded with the particle's index;
// with ROLLING_FRICTION every particle's rolling springs (x, y, z of each slot); and with SLEEPING
// every particle's last computed force and torque, which a sleeper carries.
#include "common/layout.glsl"

#define HASH_THREADS 256
layout(local_size_x = HASH_THREADS) in;

BODY_POSITION(readonly)
BODY_ORIENTATION(readonly)
BODY_VELOCITY(readonly)
BODY_ANGULAR_VELOCITY(readonly)
BODY_INFO(readonly)
BODY_IDS(readonly)
STATE_HASH_PARTIALS(writeonly)
#ifndef PAPER_LAW
CONTACT_SLOTS_0(readonly)
CONTACT_SLOTS_1(readonly)
CONTACT_SLOTS_2(readonly)
CONTACT_PAIRS(readonly)
#endif
#ifdef ROLLING_FRICTION
ROLLING_SLOTS(readonly)
#endif
// Sleep comes with ContactLaw::HertzMindlin only.
#ifdef SLEEPING
PARTICLE_FORCE(readonly)
PARTICLE_TORQUE(readonly)
#endif

shared uvec2 sharedSums[HASH_THREADS];

// MurmurHash3's finaliser: a bijection of 32-bit words that spreads every input bit.
uint fmix(uint h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

// Each step is a bijection of the lane for a fixed word and of the word for a fixed lane, so a
// change of any one word changes the body's hash in both lanes.
uvec2 absorb(uvec2 h, uint word) {
  return uvec2(fmix(h.x ^ word) + 0x9e3779b9u, fmix(h.y ^ (word * 0x27d4eb2fu)) + 0x7f4a7c15u);
}

uvec2 absorb3(uvec2 h, vec4 v) {
  h = absorb(h, floatBitsToUint(v.x));
  h = absorb(h, floatBitsToUint(v.y));
  return absorb(h, floatBitsToUint(v.z));
}

uvec2 absorb4(uvec2 h, vec4 v) {
  return absorb(absorb3(h, v), floatBitsToUint(v.w));
}

void main() {
  uint local = gl_LocalInvocationID.x;
  uint stride = gl_NumWorkGroups.x * HASH_THREADS;
  uvec2 sum = uvec2(0u);
  for (uint b = gl_GlobalInvocationID.x; b < params.bodyCount; b += stride) {
    uvec2 h = uvec2(fmix(b ^ 0x243f6a88u), fmix(b ^ 0x85a308d3u));
    h = absorb3(h, bodyPosition[b]);
    vec4 q = bodyOrientation[b];
    h = absorb3(h, q);
    h = absorb(h, floatBitsToUint(q.w));
    vec4 v = bodyVelocity[b];
    h = absorb3(h, v);
    h = absorb3(h, bodyAngularVelocity[b]);
    // The status word (docs/recording.md): alive, and the calm count above it (0 without sleep).
    h = absorb(h, ((bodyInfo[b].z & BODY_ALIVE) != 0u ? 1u : 0u) | (floatBitsToUint(v.w) << 1));
    // The body's id, where a sort of the granules by place put another body's state in its slot.
    uint id = bodyIds[b];
    if (id != b) h = absorb(h, id);
    sum += h;
  }
#ifndef PAPER_LAW
  for (uint i = gl_GlobalInvocationID.x; i < params.particleCount; i += stride) {
    uvec2 h = uvec2(fmix(i ^ 0x13198a2eu), fmix(i ^ 0x03707344u));
    for (uint g = 0u; g < uint(CONTACT_SLOTS_PER_GROUP); ++g) {
      uint entry = i * uint(CONTACT_SLOTS_PER_GROUP) + g;
      h = absorb4(h, contactSlots0[entry]);
      h = absorb4(h, contactSlots1[entry]);
      h = absorb4(h, contactSlots2[entry]);
    }
    uvec4 pairs = contactPairs[i];
    h = absorb(absorb(absorb(absorb(h, pairs.x), pairs.y), pairs.z), pairs.w);
    sum += h;
  }
#endif
#ifdef ROLLING_FRICTION
  for (uint i = gl_GlobalInvocationID.x; i < params.particleCount; i += stride) {
    uvec2 h = uvec2(fmix(i ^ 0xbe5466cfu), fmix(i ^ 0x34e90c6cu));
    for (uint k = 0u; k < uint(CONTACT_SLOTS); ++k) {
      h = absorb3(h, rollingSlots[i * uint(CONTACT_SLOTS) + k]);
    }
    sum += h;
  }
#endif
#ifdef SLEEPING
  for (uint i = gl_GlobalInvocationID.x; i < params.particleCount; i += stride) {
    uvec2 h = uvec2(fmix(i ^ 0xa4093822u), fmix(i ^ 0x299f31d0u));
    h = absorb4(h, particleForce[i]);
    h = absorb4(h, particleTorque[i]);
    sum += h;
  }
#endif
  sharedSums[local] = sum;
  barrier();
  for (uint width = HASH_THREADS / 2u; width > 0u; width >>= 1u) {
    if (local < width) sharedSums[local] += sharedSums[local + width];
    barrier();
  }
  if (local == 0u) stateHashPartials[gl_WorkGroupID.x] = sharedSums[0];
}
