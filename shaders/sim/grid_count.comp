#version 450
// List build, pass 1. Each particle's hash bucket in the grid of cells of d + skin at its present
// position, counted with an integer atomic (exact, order independent). Particles of dead bodies
// get no bucket and drop out of the grid and the lists.
#include "common/layout.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
PARTICLE_CELL(writeonly)
CELL_COUNT(coherent)

void main() {
  uint i = threadIndex();
  if (i >= params.particleCount) return;
  // The owner from particleBody: a granule that was never born (spawn_check.comp) never had
  // its state written.
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  if ((texelFetch(bodyInfoTexture, int(body)).z & BODY_ALIVE) == 0u) {
    particleCell[i] = INVALID_CELL;
    return;
  }
  uint bucket = bucketOf(cellOf(texelFetch(particlePositionTexture, int(i)).xyz));
  particleCell[i] = bucket;
  atomicAdd(cellCount[bucket], 1u);
}
