// Whether the neighbour lists are built before this substep's contacts, with no read-back: writes
// the group counts of the build's indirect dispatches (World::Impl::buildLists): the full counts
// when a build was asked for (a particle moved more than half the skin since the last build, a
// granule died, or the CPU changed the bodies or the table), zero otherwise, and clears the
// request. Run by list_check.comp, or under SLEEPING by the last workgroup of collect_active.comp:
// then a build the motion asked for lists only the `activeParticles` particles of the active
// list (COUNTER_LIST_ALL tells list_build.comp which), unless `everyList`, and builds the moving
// grid from them and the `recentParticles` (layout.glsl "Sleep"); the still grid only when
// stillGridDue (or `everyList`: then it takes every particle, and the moving grid none).
void setGroups(uint pass, uint groups) {
  uint at = uint(COUNTER_LIST_DISPATCH) + 4u * pass;
  counters[at] = groups;
  counters[at + 1u] = 1u;
  counters[at + 2u] = 1u;
}

uint groupsFor(uint threads) {
  return (threads + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
}

#ifdef SLEEPING
// Whether a build of `requested` builds the still grid again: when the CPU asked, or when the
// sleepers the moving grid held at the last build outnumbered the active particles in it and
// were more than a sixteenth of all particles.
bool stillGridDue(uint requested) {
  uint recent = counters[COUNTER_GRID_RECENT];
  return requested == LIST_REQUEST_ALL || (requested != 0u && sleepSteps.z != 0u) ||
         (requested != 0u && recent > max(counters[COUNTER_GRID_ACTIVE], counts.x / 16u));
}
#endif

// The decision and the build's group counts (the caller has COUNTERS(coherent)).
void decideListBuild(bool everyList, uint activeParticles, uint recentParticles) {
  uint requested = counters[COUNTER_LIST_REQUESTED];
  bool due = requested != 0u;
  uint particleGroups = due ? groupsFor(counts.x) : 0u;
  uint listGroups = particleGroups;
  uint gridGroups = particleGroups;
  // The table size is a power of two of at least 4096.
  uint scanGroups = due ? counts2.y / SCAN_BLOCK : 0u;
  uint sortGroups = due ? counts2.y / WORKGROUP_SIZE : 0u;
  bool still = false;
#ifdef SLEEPING
  bool all = everyList || requested == LIST_REQUEST_ALL;
  still = due && (everyList || stillGridDue(requested));
  counters[COUNTER_LIST_ALL] = all ? 1u : 0u;
  if (due && !all) listGroups = groupsFor(activeParticles);
  if (due) {
    uint gridActive = everyList ? 0u : activeParticles;
    uint gridRecent = everyList ? 0u : recentParticles;
    counters[COUNTER_GRID_ACTIVE] = gridActive;
    counters[COUNTER_GRID_RECENT] = gridRecent;
    gridGroups = groupsFor(gridActive + gridRecent);
    if (still) {
      counters[COUNTER_STILL_BUILD] = counters[COUNTER_LIST_BUILDS] + 1u;
      counters[COUNTER_STILL_BUILDS] += 1u;
    }
  }
#endif
  counters[COUNTER_LIST_REQUESTED] = 0u;
  if (due) counters[COUNTER_LIST_BUILDS] += 1u;
  setGroups(PASS_STILL_COUNT, still ? particleGroups : 0u);
  setGroups(PASS_STILL_SCAN_BLOCKS, still ? scanGroups : 0u);
  setGroups(PASS_STILL_SCAN_BLOCK_SUMS, still ? 1u : 0u);
  setGroups(PASS_STILL_SCAN_ADD, still ? scanGroups : 0u);
  setGroups(PASS_STILL_SCATTER, still ? particleGroups : 0u);
  setGroups(PASS_STILL_SORT, still ? sortGroups : 0u);
  setGroups(PASS_GRID_COUNT, gridGroups);
  setGroups(PASS_SCAN_BLOCKS, scanGroups);
  setGroups(PASS_SCAN_BLOCK_SUMS, due ? 1u : 0u);
  setGroups(PASS_SCAN_ADD, scanGroups);
  setGroups(PASS_GRID_SCATTER, gridGroups);
  setGroups(PASS_GRID_SORT, sortGroups);
  setGroups(PASS_LIST_BUILD, listGroups);
}
