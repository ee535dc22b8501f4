#version 450
// Sort of the granules by place (WorldSettings::sortInterval, docs/architecture.md "Granule
// order"), pass 1: the granules in the order of the last list build's grid, which holds the
// particles bucket by bucket, ascending inside each (under SLEEPING the moving grid). One thread
// per grid entry marks, in cellCount (all zero between builds), the entries that are the first
// particle of a granule the sort moves; the scan after it numbers them.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_PARTICLES_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
CELL_COUNT(writeonly)
#ifdef SLEEPING
BODY_GRID_BUILD_TEXTURE
COUNTERS(readonly)
#endif
#include "common/granule_order.glsl"

void main() {
  uint j = threadIndex();
  if (j >= texelFetch(cellStartTexture, int(params.hashSize)).x) return;
  uint particle = texelFetch(cellParticlesTexture, int(j)).x;
  uint body = texelFetch(particleBodyTexture, int(particle)).x;
  if (texelFetch(bodyInfoTexture, int(body)).x == particle && sortsGranule(body)) {
    cellCount[j] = 1u;
  }
}
