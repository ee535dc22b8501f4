// The hash multipliers of the grid (common/spatial_hash.glsl), fitted to the cells the particles
// occupy. The CPU's multipliers fold the table like a cube of ~hashSize^(1/3) cells a side, and a
// pile wider than that shares buckets between cells its searches then scan. A build that fits
// the grid (every build without SLEEPING; under it, one that builds the still grid, whose
// buckets the moving grids share until the next) first measures the extent of the cells it sorts
// (grid_extent.comp); every pass reads the multipliers from that extent until the next fitting
// build: rows of the extent's x span plus a cell each side, planes of its y span likewise, so a
// box of cells that fits the table gets a bucket per cell. Where no fit keeps the 27 neighbours
// of a cell in distinct buckets, the CPU's multipliers serve. The includer declares COUNTERS.

// A cell coordinate as an unsigned key in the same order (the sign bit flipped). The extent
// keeps per axis the largest key and the largest complement of a key: maxima, so that atomics
// give the same words in any order, and zero before any particle was measured.
uint extentKey(int coordinate) {
  return uint(coordinate) ^ 0x80000000u;
}

uvec2 hashMultipliers() {
  uvec2 cpu = uvec2(params.hashMultiplierY, params.hashMultiplierZ);
  uvec3 high = uvec3(counters[COUNTER_GRID_EXTENT], counters[COUNTER_GRID_EXTENT + 1],
                     counters[COUNTER_GRID_EXTENT + 2]);
  uvec3 lowComplement = uvec3(counters[COUNTER_GRID_EXTENT + 3],
                              counters[COUNTER_GRID_EXTENT + 4], counters[COUNTER_GRID_EXTENT + 5]);
  if (any(equal(high, uvec3(0u))) || any(equal(lowComplement, uvec3(0u)))) return cpu;
  uvec3 reach = high - ~lowComplement;  // cells beyond the first, per axis
  if (reach.x >= params.hashSize || reach.y >= params.hashSize) return cpu;
  uint row = reach.x + 3u;    // a free cell each side: a neighbour row starts past them
  uint plane = reach.y + 3u;  // likewise (and >= 3 rows: 27 distinct buckets, below)
  if (plane > params.hashSize / row) return cpu;
  // Offsets of up to two cells on each axis (three x-neighbours' ranges, two rows apart) stay
  // distinct and non-zero modulo the table while 2 (1 + row + row plane) < hashSize.
  uint multiplierZ = row * plane;
  if (2u * (1u + row + multiplierZ) >= params.hashSize) return cpu;
  return uvec2(row, multiplierZ);
}
