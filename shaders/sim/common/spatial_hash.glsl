// Uniform grid of cell size d folded into a power-of-two table by a linear hash. Neighbouring x
// cells map to neighbouring buckets, so the bucket-ordered arrays keep nearby particles close in
// memory, and three x-neighbours form one contiguous range. The multipliers
// (params.hashMultiplierY, Z) are chosen on the CPU so that the 27 cells around any cell fall into
// 27 distinct buckets: a gather visits each neighbour once without checking for repeats.

ivec3 cellOf(vec3 position) {
  return ivec3(floor(position * params.inverseCellSize));
}

uint bucketOf(ivec3 cell) {
  return (uint(cell.x) + uint(cell.y) * params.hashMultiplierY +
          uint(cell.z) * params.hashMultiplierZ) &
         params.hashMask;
}
