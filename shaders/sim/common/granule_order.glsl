// The sort of the granules by place (WorldSettings::sortInterval; docs/architecture.md, "Granule
// order"): which bodies it moves. The includer declares BODY_INFO_TEXTURE and, under SLEEPING,
// BODY_GRID_BUILD_TEXTURE and COUNTERS.

// Every granule that moves freely and is alive: they all have the World's granule template, so
// their slots can trade states. Under SLEEPING only those this substep computes: the build of
// every list that the sort follows (collect_active.comp asks for it) put exactly them in its
// moving grid (common/grid.glsl).
// The sleepers keep their slots, so the computed granules trade slots among themselves and the
// active lists (collect_active.comp) still name the slots this substep computes.
bool sortsGranule(uint body) {
  uint flags = texelFetch(bodyInfoTexture, int(body)).z;
  uint motion = (flags & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  bool computed = true;
#ifdef SLEEPING
  computed = texelFetch(bodyGridBuildTexture, int(body)).x == counters[COUNTER_LIST_BUILDS];
#endif
  return (flags & (BODY_ALIVE | BODY_GRANULE)) == (BODY_ALIVE | BODY_GRANULE) &&
         motion == MOTION_DYNAMIC && computed;
}
