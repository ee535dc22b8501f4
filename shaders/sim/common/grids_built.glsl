// Which grids a list build builds (common/grid.glsl has the grids): under SLEEPING the moving
// grid alone, or both when the build also builds the still grid; without SLEEPING the one grid.
// The includer declares COUNTERS under SLEEPING.

// Whether this build builds the still grid (always true without SLEEPING: the one grid).
bool buildsStillGrid() {
#ifdef SLEEPING
  return counters[COUNTER_STILL_BUILD] == counters[COUNTER_LIST_BUILDS];
#else
  return true;
#endif
}

// The tables this build fills: the moving grid's alone, or both (one without SLEEPING).
uint gridsBuilt() {
#ifdef SLEEPING
  return buildsStillGrid() ? 2u : 1u;
#else
  return 1u;
#endif
}
