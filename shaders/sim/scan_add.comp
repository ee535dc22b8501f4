#version 450
// List build, pass 5. Adds each block's offset to its 1024 exclusive sums (scan_blocks.comp says
// where each grid's are).
#include "common/layout.glsl"

#define SCAN_THREADS 256
layout(local_size_x = SCAN_THREADS) in;

CELL_START(coherent)
SCAN_BLOCK_SUMS(readonly)

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  uint add = scanBlockSums[group];
  uint base = group * (SCAN_THREADS * 4u) + gl_LocalInvocationID.x * 4u;
  uint at = base + base / params.hashSize;
  for (uint k = 0u; k < 4u; ++k) cellStart[at + k] += add;
}
