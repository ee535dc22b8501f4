// Neighbour lists (gpu_buffers.def, NEIGHBOUR_LIST, LIST_ORIGIN, LIST_NEAR): each particle that
// needs forces lists the particles of other bodies closer than d + skin at the last build,
// ascending by id. A particle's contacts are then evaluated in partner-id order whenever the lists
// were built: the skin and the moments of the builds change no bit of the result, and the lists
// are a cache that snapshots need not carry. The lists are built from the grid of the build
// (common/grid.glsl).
//
// Without sleep, listNear.w marks with bit k the entries k that were within d + near skin of the
// particle when list_near.comp last marked them, from where it stood then (listNear.xyz): it marks
// them after each build and once some particle has moved half the near skin since, so an
// unmarked entry cannot touch the particle before the next marking, and the contacts passes that
// take partners from the list test only the marked ones. It holds LIST_NEAR_COLLIDER too when the
// surface of some collider was within half the near skin of the particle's surface; no collider
// moves until the next marking (a changed collider asks for a build), so one without the bit
// touches no collider: the contacts pass that every particle runs leaves the collider code to the
// pass over the few with it.

// Entry k of particle i's list in neighbourList.
int listEntry(uint particle, uint k) {
  return int(k * params.listStride + particle);
}

// The entries of a list marked near in listNear.w `marks`, a bit each.
uint nearEntries(uint marks) {
  return marks & ((1u << NEIGHBOUR_LIST_CAPACITY) - 1u);
}

bool marksNearCollider(uint marks) {
  return (marks & LIST_NEAR_COLLIDER) != 0u;
}

// Whether a live particle with listOrigin.w `listed` (the partners the build found) finds its
// partners in the grid (the pass over searchDue) rather than in its list: it had more than the
// list holds (in a test's SEARCH_EVERY compilation, every particle). Without sleep
// list_build.comp lists such particles from this.
bool listOverflows(uint listed) {
#ifdef SEARCH_EVERY
  return true;  // a test's: every particle searched, to the same bits (searchEveryParticle)
#else
  return listed > uint(NEIGHBOUR_LIST_CAPACITY);
#endif
}
