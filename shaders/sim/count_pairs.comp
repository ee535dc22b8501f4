#version 450
// Pass 5, ContactLaw::HertzMindlin: the pair counts of the granules integrate_bodies.comp listed
// (those whose particles' slots changed in this substep, or every one when the CPU asks), one
// thread each, from the indirect command it wrote (common/contact_pairs.glsl). A pass of its own
// so that the substep of a still pile, where almost no granule counts, does not carry the
// counting's code: behind a branch in integrate_bodies.comp it cost llvmpipe most of what
// counting every granule costs, even where no lane of a batch took the branch (bench/README.md,
// "Pair counts").
#include "common/layout.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_INFO_TEXTURE
PARTICLE_BODY_TEXTURE
CONTACT_SLOTS_0_TEXTURE
CONTACT_SLOTS_1_TEXTURE
CONTACT_SLOTS_2_TEXTURE
CONTACT_PAIRS(writeonly)
PAIRS_DUE(readonly)
COUNTERS(readonly)
#include "common/contact_pairs.glsl"

// The particles of a granule (tetrahedronTemplate).
#define GRANULE_PARTICLES 4u

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
// full; the blocks of groups not in use are skipped (on a GPU a uniform branch for most warps).
// All indices are constant once unrolled.
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

void main() {
  uint t = threadIndex();
  if (t >= activeListLength(ACTIVE_PASS_PAIRS)) return;
  countPairs(texelFetch(bodyInfoTexture, int(pairsDue[t])).x);
}
