// Whether the neighbour lists are built before this substep's contacts, with no read-back: writes
// the group counts of the build's indirect dispatches (World::Impl::buildLists): the full counts
// when a build was asked for (a particle moved more than half the skin since the last build, a
// granule died, or the CPU changed the bodies or the table), zero otherwise, and clears the
// request. Run by list_check.comp, or under SLEEPING by the last workgroup of collect_active.comp:
// then a build the motion asked for lists only the `activeParticles` particles of the active
// list (COUNTER_LIST_ALL tells list_build.comp which), unless `everyList`, and sorts them and the
// `recentParticles` into the moving grid; the still grid is built only when stillGridDue (or
// `everyList`: then the moving grid takes no particle). common/grid.glsl has the two grids.
// Without sleep it also writes the group counts of list_near.comp, full after a build or when a
// particle moved half the near skin since the last marking, and clears that request.
uint groupsFor(uint threads) {
  return (threads + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
}

// The indirect command at counters[at] for `groups` workgroups, spilling into y as
// World::Impl::dispatch does (threadIndex() folds it back).
void writeGroups(uint at, uint groups) {
  uint x = min(groups, 32768u);
  counters[at] = x;
  counters[at + 1u] = x == 0u ? 0u : (groups + x - 1u) / x;
  counters[at + 2u] = 1u;
}

// Appends an entry to the list of `pass` (ACTIVE_PASS_PAIRS, _SEARCH, _COLLIDERS) and returns its
// place: the list's length is its command's fourth uint, and the command grows with it to the
// groups writeGroups would write for that length. Concurrent callers, in any order (integer
// atomics); the list's order is then the threads', so each entry's result must be its own.
uint appendToPass(uint pass) {
  uint at = uint(COUNTER_ACTIVE_DISPATCH) + 4u * pass;
  uint slot = atomicAdd(counters[at + 3u], 1u);
  if (slot % WORKGROUP_SIZE == 0u) {
    uint groups = slot / WORKGROUP_SIZE + 1u;
    atomicMax(counters[at], min(groups, 32768u));
    atomicMax(counters[at + 1u], (groups + 32767u) / 32768u);
  }
  return slot;
}

// The commands of the passes whose lists appendToPass fills, set for the substep by its first
// pass: count_pairs.comp's (integrate_bodies.comp fills its list as the substep runs; a substep
// with no granule to advance runs none), and contacts_search's and contacts_colliders', over the
// particles the contacts passes leave to them. Without sleep list_build.comp lists the search's
// for the substeps until the next build (`built`: one is due in this substep, and empties them)
// and list_near.comp the colliders' until the next marking of the lists' near part (`marked`,
// likewise), and in each substep the contacts pass adds to contacts_colliders' the particles with
// more slots in use than it loads, and contacts_colliders to the search's those with more than it
// loads; under SLEEPING contacts.comp fills the search's as the substep runs. Every other list
// starts empty.
void clearRunningCommands(bool built, bool marked) {
  for (uint pass = ACTIVE_PASS_PAIRS; pass <= ACTIVE_PASS_COLLIDERS; ++pass) {
    uint length = 0u;
#ifndef SLEEPING
    if (pass == ACTIVE_PASS_SEARCH || pass == ACTIVE_PASS_COLLIDERS) {
      bool search = pass == ACTIVE_PASS_SEARCH;
      uint listed = search ? COUNTER_SEARCH_LISTED : COUNTER_COLLIDERS_LISTED;
      if (search ? built : marked) counters[listed] = 0u;
      length = counters[listed];
    }
#endif
    uint at = uint(COUNTER_ACTIVE_DISPATCH) + 4u * pass;
    writeGroups(at, groupsFor(length));
    counters[at + 3u] = length;
  }
}

void setGroups(uint pass, uint groups) {
  writeGroups(uint(COUNTER_LIST_DISPATCH) + 4u * pass, groups);
}

// Whether this substep marks the lists' near part, once decideListBuild has decided.
bool nearMarkingDue() {
  return counters[uint(COUNTER_LIST_DISPATCH) + 4u * PASS_LIST_NEAR] != 0u;
}

#ifdef SLEEPING
// Whether a build of `requested` (COUNTER_LIST_REQUESTED) builds the still grid again: when the
// CPU asked for it, or when the recent sleepers in the last moving grid outnumbered its active
// particles and were more than a sixteenth of all particles.
bool stillGridDue(uint requested) {
  uint recent = counters[COUNTER_GRID_RECENT];
  return requested == LIST_REQUEST_ALL || (requested != 0u && params.oneGrid != 0u) ||
         (requested != 0u &&
          recent > max(counters[COUNTER_GRID_ACTIVE], params.particleCount / 16u));
}
#endif

// The decision and the build's group counts (the caller has COUNTERS(coherent)); whether a build
// is due.
bool decideListBuild(bool everyList, uint activeParticles, uint recentParticles) {
  uint requested = counters[COUNTER_LIST_REQUESTED];
  bool due = requested != 0u;
  uint particleGroups = due ? groupsFor(params.particleCount) : 0u;
  uint listGroups = particleGroups;
  uint gridGroups = particleGroups;
  // The table size is a power of two of at least 4096; one table per grid built.
  uint scanGroups = due ? params.hashSize / SCAN_BLOCK : 0u;
  uint sortGroups = due ? params.hashSize / WORKGROUP_SIZE : 0u;
  // A build that builds every grid fits them to the sand (common/grid_fit.glsl).
  bool fits = due;
#ifdef SLEEPING
  bool all = everyList || requested == LIST_REQUEST_ALL;
  counters[COUNTER_LIST_ALL] = all ? 1u : 0u;
  if (due && !all) listGroups = groupsFor(activeParticles);
  if (due) {
    bool still = everyList || stillGridDue(requested);
    uint gridActive = everyList ? 0u : activeParticles;
    uint gridRecent = still ? 0u : recentParticles;
    fits = still;
    counters[COUNTER_GRID_ACTIVE] = gridActive;
    counters[COUNTER_GRID_RECENT] = gridRecent;
    if (still) {
      counters[COUNTER_STILL_BUILD] = counters[COUNTER_LIST_BUILDS] + 1u;
      counters[COUNTER_STILL_BUILDS] += 1u;
      scanGroups *= 2u;
      sortGroups *= 2u;
    } else {
      gridGroups = groupsFor(gridActive + gridRecent);
    }
  }
#endif
  if (fits) {
    for (uint word = 0u; word < 6u; ++word) counters[COUNTER_GRID_EXTENT + word] = 0u;
  }
  counters[COUNTER_LIST_REQUESTED] = 0u;
  if (due) counters[COUNTER_LIST_BUILDS] += 1u;
  setGroups(PASS_GRID_EXTENT, fits ? particleGroups : 0u);
  setGroups(PASS_GRID_COUNT, gridGroups);
  setGroups(PASS_SCAN_BLOCKS, scanGroups);
  setGroups(PASS_SCAN_BLOCK_SUMS, due ? 1u : 0u);
  setGroups(PASS_SCAN_ADD, scanGroups);
  setGroups(PASS_GRID_SCATTER, gridGroups);
  setGroups(PASS_GRID_SORT, sortGroups);
  setGroups(PASS_LIST_BUILD, listGroups);
#ifndef SLEEPING
  // The near part of the lists, marked again after a build or once some particle moved half the
  // near skin since the last marking.
  bool nearDue = due || counters[COUNTER_NEAR_REQUESTED] != 0u;
  counters[COUNTER_NEAR_REQUESTED] = 0u;
  if (nearDue) counters[COUNTER_NEAR_MARKINGS] += 1u;
  setGroups(PASS_LIST_NEAR, nearDue ? groupsFor(params.particleCount) : 0u);
#endif
  return due;
}
