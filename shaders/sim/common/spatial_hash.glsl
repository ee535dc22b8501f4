// Uniform grid of cell size d + skin folded into a power-of-two table by a linear hash, bucket
// x + y * multipliers.x + z * multipliers.y modulo the table. Neighbouring x cells map to
// neighbouring buckets, so the bucket-ordered arrays keep nearby particles close in memory, and
// three x-neighbours form one contiguous range. The multipliers send the 27 cells around any cell
// to 27 distinct buckets, so a gather visits each neighbour once without checking for repeats:
// fitted to the sand's extent where it fits the table (common/grid_fit.glsl), else the CPU's
// (params.hashMultiplierY, Z).

ivec3 cellOf(vec3 position) {
  return ivec3(floor(position * params.inverseCellSize));
}

uint bucketOf(ivec3 cell, uvec2 multipliers) {
  return (uint(cell.x) + uint(cell.y) * multipliers.x + uint(cell.z) * multipliers.y) &
         params.hashMask;
}
