#version 450
// Sort of the granules by place, pass 2: the granule of each marked grid entry, by its number in
// the grid's order (bodyOrder.x), and the marks cleared. The count goes to COUNTER_ORDER_SEQUENCE
// for order_moves.comp to check against the slots it fills.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_BODY_TEXTURE
CELL_COUNT(coherent)
BODY_ORDER(writeonly)
COUNTERS(writeonly)

void main() {
  uint j = threadIndex();
  if (j == 0u) {
    counters[COUNTER_ORDER_SEQUENCE] = texelFetch(cellStartTexture, int(params.hashSize)).x;
  }
  if (j >= params.particleCount || cellCount[j] == 0u) return;
  cellCount[j] = 0u;
  uint particle = texelFetch(cellParticlesTexture, int(j)).x;
  uint rank = texelFetch(cellStartTexture, int(j)).x;
  bodyOrder[rank].x = texelFetch(particleBodyTexture, int(particle)).x;
}
