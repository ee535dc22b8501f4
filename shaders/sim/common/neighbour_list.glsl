// Neighbour lists (gpu_buffers.def, NEIGHBOUR_LIST, LIST_ORIGIN): each particle that needs forces
// lists the particles of other bodies closer than d + skin at the last build, ascending by id. A
// particle's contacts are then evaluated in partner-id order whenever the lists were built: the
// skin and the moments of the builds change no bit of the result, and the lists are a cache that
// snapshots need not carry. The includer declares CELL_START_TEXTURE and CELL_PARTICLES_TEXTURE and
// includes spatial_hash.glsl.

// Entry k of particle i's list in neighbourList.
int listEntry(uint particle, uint k) {
  return int(k * params.listStride + particle);
}

// The grid of the last build is scanned as 9 rows of three x-neighbour cells around a cell: one
// range of consecutive buckets per row unless the row wraps around the table, then three.
uint rowParts(ivec3 cell, int row) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1));
  return ((centre - 1u) & params.hashMask) < ((centre + 1u) & params.hashMask) ? 1u : 3u;
}

// [begin, end) of the bucket-ordered slots of part `part` of row `row` (see rowParts).
uvec2 rowSlots(ivec3 cell, int row, uint part, uint parts) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1));
  uint first =
      parts == 1u ? (centre - 1u) & params.hashMask : (centre + part - 1u) & params.hashMask;
  uint last = parts == 1u ? (centre + 1u) & params.hashMask : first;
  return uvec2(texelFetch(cellStartTexture, int(first)).x,
               texelFetch(cellStartTexture, int(last + 1u)).x);
}
