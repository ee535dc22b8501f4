// Whether the neighbour lists are built before this substep's contacts, with no read-back: writes
// the group counts of the build's indirect dispatches (World::Impl::buildLists): the full counts
// when a build was asked for (a particle moved more than half the skin since the last build, a
// granule died, or the CPU changed the bodies or the table), zero otherwise, and clears the
// request. Run by list_check.comp, or under SLEEPING by the last workgroup of collect_active.comp:
// then a build the motion asked for lists only the `activeParticles` particles of the active
// list (COUNTER_LIST_ALL tells list_build.comp which), unless `everyList`.
void setGroups(uint pass, uint groups) {
  uint at = uint(COUNTER_LIST_DISPATCH) + 4u * pass;
  counters[at] = groups;
  counters[at + 1u] = 1u;
  counters[at + 2u] = 1u;
}

// The decision and the build's group counts (the caller has COUNTERS(coherent)).
void decideListBuild(bool everyList, uint activeParticles) {
  uint requested = counters[COUNTER_LIST_REQUESTED];
  bool due = requested != 0u;
  counters[COUNTER_LIST_REQUESTED] = 0u;
  if (due) counters[COUNTER_LIST_BUILDS] += 1u;
  uint particleGroups = due ? (params.particleCount + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE : 0u;
  uint listGroups = particleGroups;
#ifdef SLEEPING
  bool all = everyList || requested == LIST_REQUEST_ALL;
  counters[COUNTER_LIST_ALL] = all ? 1u : 0u;
  if (due && !all) listGroups = (activeParticles + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
#endif
  // The table size is a power of two of at least 4096.
  uint scanGroups = due ? params.hashSize / SCAN_BLOCK : 0u;
  setGroups(PASS_GRID_COUNT, particleGroups);
  setGroups(PASS_SCAN_BLOCKS, scanGroups);
  setGroups(PASS_SCAN_BLOCK_SUMS, due ? 1u : 0u);
  setGroups(PASS_SCAN_ADD, scanGroups);
  setGroups(PASS_GRID_SCATTER, particleGroups);
  setGroups(PASS_GRID_SORT, due ? params.hashSize / WORKGROUP_SIZE : 0u);
  setGroups(PASS_LIST_BUILD, listGroups);
}
