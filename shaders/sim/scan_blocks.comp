#version 450
// Pass 2a. Exclusive prefix sum of the bucket counts, 1024 per workgroup (4 per thread, then a
// work-efficient scan in shared memory); each workgroup's total goes to scanBlockSums.
#include "common/layout.glsl"

#define SCAN_THREADS 256
layout(local_size_x = SCAN_THREADS) in;

CELL_COUNT(readonly)
CELL_START(writeonly)
SCAN_BLOCK_SUMS(writeonly)

shared uint partial[SCAN_THREADS];

void main() {
  uint local = gl_LocalInvocationID.x;
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint base = group * (SCAN_THREADS * 4u) + local * 4u;
  uint size = counts2.y;
  uvec4 v = uvec4(base < size ? cellCount[base] : 0u, base + 1u < size ? cellCount[base + 1u] : 0u,
                  base + 2u < size ? cellCount[base + 2u] : 0u, base + 3u < size ? cellCount[base + 3u] : 0u);
  uint threadSum = v.x + v.y + v.z + v.w;
  partial[local] = threadSum;
  barrier();
  // Hillis-Steele inclusive scan over the 256 thread sums.
  for (uint offset = 1u; offset < SCAN_THREADS; offset <<= 1u) {
    uint add = local >= offset ? partial[local - offset] : 0u;
    barrier();
    partial[local] += add;
    barrier();
  }
  uint exclusive = partial[local] - threadSum;
  if (base < size) cellStart[base] = exclusive;
  if (base + 1u < size) cellStart[base + 1u] = exclusive + v.x;
  if (base + 2u < size) cellStart[base + 2u] = exclusive + v.x + v.y;
  if (base + 3u < size) cellStart[base + 3u] = exclusive + v.x + v.y + v.z;
  if (local == SCAN_THREADS - 1u) scanBlockSums[group] = partial[local];
}
