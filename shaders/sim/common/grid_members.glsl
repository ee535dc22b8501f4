// Which particles a list build sorts, and into which grid (grid_count.comp, grid_scatter.comp;
// common/grid.glsl has the grids). Without SLEEPING: every particle, into the one grid. Under
// SLEEPING a build that builds the still grid takes every particle; one that keeps it takes the
// moving grid's alone: the active list's (COUNTER_GRID_ACTIVE of them), then the recent
// sleepers' (COUNTER_GRID_RECENT, from the end of activeParticles). The includer declares
// COUNTERS and, under SLEEPING, ACTIVE_PARTICLES.

// Whether this build builds the still grid (always true without SLEEPING: the one grid).
bool stillGridBuilt() {
#ifdef SLEEPING
  return counters[COUNTER_STILL_BUILD] == counters[COUNTER_LIST_BUILDS];
#else
  return true;
#endif
}

// The grids this build builds: the moving grid's table alone, or both (one without SLEEPING).
uint gridsBuilt() {
#ifdef SLEEPING
  return stillGridBuilt() ? 2u : 1u;
#else
  return 1u;
#endif
}

// The particle that thread t sorts, or INVALID_CELL when it has none.
uint gridParticle(uint t) {
#ifdef SLEEPING
  if (!stillGridBuilt()) {
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
