#version 450
// List build, pass 1. Each particle's hash bucket in the grid of cells of d + skin at its present
// position, counted with an integer atomic (exact, order independent). Particles of dead bodies
// get no bucket and drop out of the grid and the lists. Under SLEEPING it runs for each of the
// two grids (common/grid_members.glsl); the still grid's stamps its bodies as its own.
#include "common/layout.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
CELL_COUNT(coherent)
#ifdef STILL_GRID
BODY_GRID_BUILD(coherent)
COUNTERS(readonly)
#else
PARTICLE_CELL(writeonly)
#endif
#if defined(SLEEPING) && !defined(STILL_GRID)
ACTIVE_PARTICLES(readonly)
RECENT_PARTICLES(readonly)
COUNTERS(readonly)
#endif
#ifdef SLEEPING
LIST_ORIGIN(coherent)
LIST_BUILT(writeonly)
#endif
#include "common/grid_members.glsl"

void main() {
  uint i = gridParticle(threadIndex());
  if (i == INVALID_CELL) return;
  // The owner from particleBody: a granule that was never born (spawn_check.comp) never had
  // its state written.
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  uvec4 info = texelFetch(bodyInfoTexture, int(body));
  if (!inGrid(body, info.z)) {
#ifndef STILL_GRID
    particleCell[i] = INVALID_CELL;
#endif
    return;
  }
  vec3 position = texelFetch(particlePositionTexture, int(i)).xyz;
  uint bucket = bucketOf(cellOf(position));
#ifdef SLEEPING
  // A sleeper sorted here whose list this build does not build (the active particles' it does)
  // measures how far it moves from here, and finds its partners in the grid until its next
  // list: so it is never more than half the skin from where the grid holds it.
#ifdef STILL_GRID
  bool passedOver = true;
#else
  bool passedOver = threadIndex() >= counters[COUNTER_GRID_ACTIVE];
#endif
  if (passedOver) {
    listOrigin[i].xyz = position;
    listBuilt[i] = 0u;  // no build's: builds count from 1
  }
#endif
#ifdef STILL_GRID
  // Below every later build's stamp: the still grid holds the body until the moving grid
  // takes it (its other particles still read a stamp other than this build's).
  if (info.x == i) bodyGridBuild[body] = 0u;
#else
  particleCell[i] = bucket;
#endif
  atomicAdd(cellCount[bucket], 1u);
}
