#version 450
// List build, pass 4. Exclusive scan of the per-block totals of each grid built by one workgroup,
// in chunks with a running carry; each grid's total (particles in it) goes to its cellStart entry
// tableSize.
#include "common/layout.glsl"

#define SCAN_THREADS 1024
layout(local_size_x = SCAN_THREADS) in;

CELL_START(writeonly)
SCAN_BLOCK_SUMS(coherent)
#ifdef SLEEPING
COUNTERS(readonly)
#endif
#include "common/grids_built.glsl"

shared uint partial[SCAN_THREADS];
shared uint carry;

void main() {
  uint local = gl_LocalInvocationID.x;
  uint blocks = params.hashSize / SCAN_BLOCK;
  for (uint grid = 0u; grid < gridsBuilt(); ++grid) {
    if (local == 0u) carry = 0u;
    barrier();
    for (uint chunk = 0u; chunk < blocks; chunk += SCAN_THREADS) {
      uint index = chunk + local;
      uint value = index < blocks ? scanBlockSums[grid * blocks + index] : 0u;
      partial[local] = value;
      barrier();
      for (uint offset = 1u; offset < SCAN_THREADS; offset <<= 1u) {
        uint add = local >= offset ? partial[local - offset] : 0u;
        barrier();
        partial[local] += add;
        barrier();
      }
      if (index < blocks) scanBlockSums[grid * blocks + index] = carry + partial[local] - value;
      barrier();
      if (local == 0u) carry += partial[SCAN_THREADS - 1u];
      barrier();
    }
    if (local == 0u) cellStart[grid * (params.hashSize + 1u) + params.hashSize] = carry;
  }
}
