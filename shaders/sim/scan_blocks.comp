#version 450
// List build, pass 3. Exclusive prefix sum of the bucket counts of each grid built, 1024 per
// workgroup (4 per thread, then a work-efficient scan in shared memory); each workgroup's total
// goes to scanBlockSums. Under SLEEPING the still grid's table follows the moving grid's
// (gpu_buffers.def, CELL_*), its sums one entry further on.
#include "common/layout.glsl"

#define SCAN_THREADS 256
layout(local_size_x = SCAN_THREADS) in;

CELL_COUNT_TEXTURE
CELL_START(writeonly)
SCAN_BLOCK_SUMS(writeonly)

shared uint partial[SCAN_THREADS];

void main() {
  uint local = gl_LocalInvocationID.x;
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint base = group * (SCAN_THREADS * 4u) + local * 4u;
  // The table size is a power of two of at least 4096, so every block is full and in one grid.
  uvec4 v = uvec4(texelFetch(cellCountTexture, int(base)).x, texelFetch(cellCountTexture, int(base + 1u)).x,
                  texelFetch(cellCountTexture, int(base + 2u)).x, texelFetch(cellCountTexture, int(base + 3u)).x);
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
  uint at = base + base / params.hashSize;
  cellStart[at] = exclusive;
  cellStart[at + 1u] = exclusive + v.x;
  cellStart[at + 2u] = exclusive + v.x + v.y;
  cellStart[at + 3u] = exclusive + v.x + v.y + v.z;
  if (local == SCAN_THREADS - 1u) scanBlockSums[group] = partial[local];
}
