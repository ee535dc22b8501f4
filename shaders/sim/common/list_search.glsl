// The search of a list build (common/neighbour_list.glsl): over the 27 cells around a particle in
// the grids of the last build (common/grid.glsl), the particles of other bodies closer than
// d + skin that it could touch (not two immovable ones), ascending by id. list_build.comp runs it
// at the build, from where every particle stands; contacts.comp runs it later for a list the
// build passed over, from where the build sorted each particle (listOrigin): the same places, as
// no particle moves more than half the skin from there before the next build, so the list holds
// every partner until then. The includer declares PARTICLE_POSITION_TEXTURE,
// PARTICLE_VELOCITY_TEXTURE and the grids' buffers, includes common/grid.glsl, and defines
// searchPosition(id): where the search measures particle id from.

// Above every particle id: the entries of a list not yet filled.
#define NO_LIST_ENTRY 0xffffffffu

// The particles within reach of `at` for a particle of `body` with `inverseMass`: the
// NEIGHBOUR_LIST_CAPACITY smallest ids in `ids`, ascending, and how many there were.
uint searchList(vec3 at, uint body, float inverseMass, out uint ids[NEIGHBOUR_LIST_CAPACITY]) {
  uint count = 0u;
  for (int j = 0; j < NEIGHBOUR_LIST_CAPACITY; ++j) ids[j] = NO_LIST_ENTRY;
  ivec3 cell = cellOf(at);
  uvec2 multipliers = hashMultipliers();
  uint stillBuild = stillGridBuild();
  for (int row = 0; row < 9; ++row) {
    uint parts = rowParts(cell, row, multipliers);
    for (uint part = 0u; part < parts; ++part) {
      uvec4 slots = rowSlots(cell, row, part, parts, multipliers);
      for (uint k = 0u; k < rowEntries(slots); ++k) {
        uint id = rowParticle(slots, k);
        uint otherBody = floatBitsToUint(texelFetch(particlePositionTexture, int(id)).w);
        if (otherBody == body) continue;
        vec3 d = at - searchPosition(id);
        if (dot(d, d) >= params.listReachSquared) continue;
        float otherInverseMass = texelFetch(particleVelocityTexture, int(id)).w;
        if (max(inverseMass, 0.0) + max(otherInverseMass, 0.0) == 0.0) continue;
        if (!rowHolds(slots, k, otherBody, stillBuild)) continue;
        // Keep the smallest ids, in order: inserted into the sorted list, every entry at a
        // constant index (llvmpipe writes an array at an index that differs between lanes lane by
        // lane). The largest falls off the end of a full list.
        for (int j = NEIGHBOUR_LIST_CAPACITY - 1; j > 0; --j) {
          ids[j] = min(ids[j], max(ids[j - 1], id));
        }
        ids[0] = min(ids[0], id);
        ++count;
      }
    }
  }
  return count;
}
