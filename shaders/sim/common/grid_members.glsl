// Which particles a grid pass puts in its grid (grid_count.comp, grid_scatter.comp). Without
// SLEEPING: every particle. Under SLEEPING the moving grid takes the active list's particles and
// then the recentParticles, as the build's decision counted them (COUNTER_GRID_ACTIVE,
// COUNTER_GRID_RECENT); the still grid (STILL_GRID) looks at every particle and takes those of
// bodies the moving grid did not take (layout.glsl "Sleep"). The includer declares what this
// reads, and threadIndex() is thread t.

// The particle of thread t, or INVALID_CELL when t has none.
uint gridParticle(uint t) {
#if defined(SLEEPING) && !defined(STILL_GRID)
  uint fromActive = counters[COUNTER_GRID_ACTIVE];
  if (t < fromActive) return activeParticles[t];
  if (t < fromActive + counters[COUNTER_GRID_RECENT]) return recentParticles[t - fromActive];
  return INVALID_CELL;
#else
  return t < counts.x ? t : INVALID_CELL;
#endif
}

// Whether particle i, of `body` with flags `flags`, goes into the grid: its body is alive (a
// granule that was never born has no state), and for the still grid the moving grid of this
// build does not hold it.
bool inGrid(uint body, uint flags) {
  if ((flags & BODY_ALIVE) == 0u) return false;
#ifdef STILL_GRID
  return bodyGridBuild[body] != counters[COUNTER_LIST_BUILDS];
#else
  return true;
#endif
}
