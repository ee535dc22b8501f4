// Contact slots of ContactLaw::HertzMindlin (gpu_buffers.def, CONTACT_SLOTS_*): the state a contact
// keeps from one substep to the next. Each particle owns CONTACT_SLOTS slots; contacts.comp
// matches every contact it finds to the slot of the same partner from the previous substep and
// writes the slots again in the order it found the contacts (the grid's fixed order, then the
// colliders'), so the state is a pure function of the previous state and the positions.
//
// A slot's key (w, uint bits): the partner particle's id + 1, or SLOT_COLLIDER | collider * 8 +
// face for a collider contact; SLOT_EMPTY (0, so that zeroed buffers hold free slots) marks a
// free slot.

#define SLOT_COLLIDER 0x80000000u
#define SLOT_EMPTY 0u
// Faces a collider may present to one particle (a container box's six walls).
#define SLOT_COLLIDER_FACES 8u

uint particleSlotKey(uint particle) {
  return particle + 1u;
}

uint colliderSlotKey(Collider c, uint face) {
  return SLOT_COLLIDER | (floatBitsToUint(c.material.w) * SLOT_COLLIDER_FACES + face);
}

// Entry of slot k of particle `particle` in its group buffer.
uint slotEntry(uint particle, uint k) {
  return particle * uint(CONTACT_SLOTS_PER_GROUP) + k % uint(CONTACT_SLOTS_PER_GROUP);
}

// Entry of slot k of particle `particle` in rollingSlots (ROLLING_FRICTION).
int rollingEntry(uint particle, uint k) {
  return int(particle * uint(CONTACT_SLOTS) + k);
}

// The pair count n of slot k from contactPairs (one byte per slot), at least 1 (a slot written
// after the counts were taken, by a restore, counts as one).
uint slotPairs(uvec4 pairs, uint k) {
  return max(1u, (pairs[k / 4u] >> (8u * (k % 4u))) & 0xffu);
}
