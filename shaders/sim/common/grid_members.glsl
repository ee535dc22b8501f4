// Which particles a list build sorts, and into which grid (grid_count.comp, grid_scatter.comp;
// common/grid.glsl has the grids). Without SLEEPING: every particle, into the one grid. Under
// SLEEPING a build that builds the still grid takes every particle; one that keeps it takes the
// moving grid's alone: the active list's (COUNTER_GRID_ACTIVE of them), then the recent
// sleepers' (COUNTER_GRID_RECENT, from the end of activeParticles). The includer declares
// COUNTERS and ACTIVE_PARTICLES under SLEEPING.
#include "grids_built.glsl"

// The particle that thread t sorts, or INVALID_CELL when it has none.
uint gridParticle(uint t) {
#ifdef SLEEPING
  if (!buildsStillGrid()) {
    uint fromActive = counters[COUNTER_GRID_ACTIVE];
    if (t < fromActive) return activeParticles[t];
    if (t < fromActive + counters[COUNTER_GRID_RECENT]) {
      return activeParticles[params.particleCount - 1u - (t - fromActive)];
    }
    return INVALID_CELL;
  }
#endif
  return t < params.particleCount ? t : INVALID_CELL;
}
