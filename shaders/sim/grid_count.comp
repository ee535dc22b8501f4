#version 450
// List build, pass 2. Each particle's hash bucket in the grid of cells of d + skin at its present
// position (common/grid_fit.glsl), counted with an integer atomic (exact, order independent).
// Particles of dead bodies get no bucket and drop out of the grid and the lists. Under SLEEPING
// the particles are those of common/grid_members.glsl, and a build of the still grid puts in the
// moving grid only the bodies collect_active.comp stamped for this build (the computed ones), the
// others in the still grid. A particle sorted without its list being built (into the still grid,
// or a recent sleeper) measures how far it moves from where it was sorted.
#include "common/layout.glsl"
#include "common/spatial_hash.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_INFO_TEXTURE
PARTICLE_CELL(writeonly)
CELL_COUNT(coherent)
COUNTERS(readonly)
#ifdef SLEEPING
ACTIVE_PARTICLES(readonly)
BODY_GRID_BUILD(coherent)
LIST_ORIGIN(coherent)
LIST_BUILT(writeonly)
#endif
#include "common/grid_members.glsl"
#include "common/grid_fit.glsl"

void main() {
  uint t = threadIndex();
  uint i = gridParticle(t);
  if (i == INVALID_CELL) return;
  // The owner from particleBody: a granule that was never born (spawn_check.comp) never had
  // its state written.
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  uvec4 info = texelFetch(bodyInfoTexture, int(body));
  if ((info.z & BODY_ALIVE) == 0u) {
    particleCell[i] = INVALID_CELL;
    return;
  }
  vec3 position = texelFetch(particlePositionTexture, int(i)).xyz;
  uint cell = bucketOf(cellOf(position), hashMultipliers());
#ifdef SLEEPING
  bool listedNow = t < counters[COUNTER_GRID_ACTIVE];
  if (buildsStillGrid()) {
    uint build = counters[COUNTER_LIST_BUILDS];
    listedNow = bodyGridBuild[body] == build;
    if (!listedNow && params.oneGrid == 0u) {
      cell += params.hashSize;
      // Older than the still grid from now on (whatever the slot held before; every particle of
      // the body reads a stamp other than this build's, also after this write).
      if (info.x == i) bodyGridBuild[body] = 0u;
    }
  }
  if (!listedNow) {
    listOrigin[i].xyz = position;
    listBuilt[i] = 0u;  // no build's: builds count from 1
  }
#endif
  particleCell[i] = cell;
  atomicAdd(cellCount[cell], 1u);
}
