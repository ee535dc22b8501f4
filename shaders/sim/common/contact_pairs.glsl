// The pair counts of ContactLaw::HertzMindlin (gpu_buffers.def, CONTACT_PAIRS): after the contacts
// of a substep, each body counts, for each of its particles' slots, how many of its slots name the
// same partner (the partner particle's body, or the collider face). The next substep's contacts
// share the two bodies' masses among those n contacts, m* = 1 / (n (1/M_a + 1/M_b)), so that a body
// meeting a surface with n particles at once gets the restitution a single contact would (Kodam et
// al. 2010). Both bodies of a pair count the same contacts, so both sides of every contact use the
// same n. The counts are a function of the slots' partners and their order alone, so a granule
// counts again only when contacts.comp says that one of its particles' slots changed
// (particleTorque.w) or the CPU, after it changed or restored the bodies, asks for every count
// (COUNTER_RECOUNT_PAIRS): in a still pile almost no granule counts (a larger body counts in
// every substep). The includer declares PARTICLE_BODY_TEXTURE and CONTACT_SLOTS_*_TEXTURE.

// No partner: a free slot (never a body index nor a collider key).
#define PARTNER_NONE 0xffffffffu

// The partner a slot names: the owning body of its partner particle, or the collider key itself
// (bit 31 set, so never a body index); PARTNER_NONE for a free slot.
uint slotPartner(uint particle, uint k) {
  int entry = int(slotEntry(particle, k));
  vec4 slot = k < 4u ? texelFetch(contactSlots0Texture, entry)
                     : (k < 8u ? texelFetch(contactSlots1Texture, entry)
                               : texelFetch(contactSlots2Texture, entry));
  uint key = floatBitsToUint(slot.w);
  if (key == SLOT_EMPTY) return PARTNER_NONE;
  if ((key & SLOT_COLLIDER) != 0u) return key;
  return texelFetch(particleBodyTexture, int(key - 1u)).x;
}

// The four slots of one component of contactPairs (slots 4 group .. 4 group + 3).
uvec4 slotPartners(uint particle, uint group) {
  return uvec4(slotPartner(particle, 4u * group), slotPartner(particle, 4u * group + 1u),
               slotPartner(particle, 4u * group + 2u), slotPartner(particle, 4u * group + 3u));
}

// Slots in use among four partners (slots fill from the first on).
uint slotsInUse(uvec4 partners) {
  uvec4 used = uvec4(notEqual(partners, uvec4(PARTNER_NONE)));
  return used.x + used.y + used.z + used.w;
}

// Four pair counts, one byte each, as contactPairs holds them (a free slot counts 0).
uint packPairs(uvec4 partners, uvec4 counts) {
  counts = min(counts, uvec4(255u));
  counts = mix(counts, uvec4(0u), equal(partners, uvec4(PARTNER_NONE)));
  return counts.x | (counts.y << 8u) | (counts.z << 16u) | (counts.w << 24u);
}
