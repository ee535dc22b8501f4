#version 450
// SLEEPING, first pass of every substep, one thread per COLLECT_CHUNK bodies: lists what this
// substep computes.
// A body is active when it is alive, not static, and awake or touched by something awake in the
// last substep (its count is calmTouched(), which this pass takes back to plain asleep); an active
// granule goes into activeBodies (integrate_bodies.comp), an active large body's entry into
// activeLargeBodies (integrate_large_bodies.comp), the particles of every active body into
// activeParticles (contacts.comp). Each thread takes the places of its chunk's entries in the
// lists with one atomic add per list, if it has any: the lists are in any order, a chunk's
// entries together in body order (each entry's result is its own); the last workgroup to
// finish writes the two passes' indirect commands, clears the totals for the next substep (and
// the commands of clearRunningCommands) and decides on the list build. When a build is due it
// stamps the bodies that go into its moving grid (BODY_GRID_BUILD): the computed ones and, unless
// the still grid is built again, the recent sleepers, whose particles it lists from the end of
// activeParticles (common/grid.glsl).
// In a substep that sorts the granules by place (COUNTER_GRANULE_SORT) it writes the sort's
// commands (COUNTER_SORT_DISPATCH): when it listed something to compute, full, with a build of
// every list, whose moving grid the sort follows; otherwise zero, so that sleeping sand is not
// sorted (as a frame that skips the substep does not sort it).
// So the passes that follow cost what the awake sand costs, and nothing is read back. A chunk
// whose last scan listed nothing is marked quiet (QUIET_CHUNKS) and passed over until something
// may have changed it, but at a build that lists the recent sleepers: so this pass, too, costs
// about what the awake sand costs.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_INFO_TEXTURE
BODY_VELOCITY_TEXTURE
BODY_VELOCITY(writeonly)
ACTIVE_BODIES(writeonly)
ACTIVE_PARTICLES(writeonly)
ACTIVE_LARGE_BODIES(writeonly)
BODY_GRID_BUILD(coherent)
QUIET_CHUNKS(restrict)
COUNTERS(coherent)
#include "common/list_decision.glsl"

// A thread lists a chunk of COLLECT_CHUNK consecutive bodies (layout.glsl). Its places come
// from atomics rather than a scan in shared memory, whose barriers llvmpipe runs as coroutine
// switches: they cost more than the atomics, and a quiet chunk needs neither.

// The command of `pass` for `entries` threads of WORKGROUP_SIZE, spilling into y as
// World::Impl::dispatch does; the fourth uint holds `entries`.
void writeCommand(uint pass, uint entries) {
  uint at = uint(COUNTER_ACTIVE_DISPATCH) + 4u * pass;
  writeGroups(at, groupsFor(entries));
  counters[at + 3u] = entries;
}

// The sort's commands (World::Impl::sortGranules): over the particles, the bodies, the blocks of
// the grid's table and one workgroup for the block sums; none unless `sorts`.
void writeSortCommands(bool sorts) {
  uint groups[SORT_PASSES] = uint[](groupsFor(params.particleCount), groupsFor(params.bodyCount),
                                    params.hashSize / SCAN_BLOCK, 1u);
  for (uint pass = 0u; pass < uint(SORT_PASSES); ++pass) {
    writeGroups(uint(COUNTER_SORT_DISPATCH) + 4u * pass, sorts ? groups[pass] : 0u);
  }
}

// Whether body b is computed this substep, its info and its calm count; and, at a build that
// keeps the still grid (`recentDue`), whether it is a recent sleeper: one the moving grid took
// at some build since the still grid was built (`stillBuild`).
bool computed(uint b, bool recentDue, uint stillBuild, out uvec4 info, out uint calm,
              out bool recent) {
  info = texelFetch(bodyInfoTexture, int(b));
  uint motion = (info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  // The thread reads its own body's count before it writes it; no other thread touches it.
  calm = floatBitsToUint(texelFetch(bodyVelocityTexture, int(b)).w);
  bool movable = (info.z & BODY_ALIVE) != 0u && motion != MOTION_STATIC;
  bool listed = movable && calm != params.sleepSubsteps;
  recent = recentDue && movable && !listed && bodyGridBuild[b] >= stillBuild;
  return listed;
}

void main() {
  uint local = gl_LocalInvocationID.x;
  uint chunk = threadIndex();
  uint first = chunk * COLLECT_CHUNK;
  uint end = min(first + COLLECT_CHUNK, params.bodyCount);
  // Every workgroup reads these before the last one changes them (decideListBuild).
  uint requested = counters[COUNTER_LIST_REQUESTED];
  // A sort needs a build of every list, if it sorts (then something is computed, and stamped
  // below; otherwise nothing is, and any other build due is made a build of every list too).
  bool sortRequested = counters[COUNTER_GRANULE_SORT] == SORT_REQUESTED;
  if (sortRequested) requested = LIST_REQUEST_ALL;
  bool recentDue = requested != 0u && !stillGridDue(requested);
  uint build = counters[COUNTER_LIST_BUILDS] + 1u;  // the number of the build, if one is due
  uint stillBuild = counters[COUNTER_STILL_BUILD];
  uint bodies = 0u;
  uint larges = 0u;
  uint particles = 0u;
  uint recents = 0u;
  // The thread's chunk, unless it is quiet (the recent sleepers in it are not).
  if (first < end && !recentDue && quietChunks[chunk] != 0u) end = first;
  for (uint b = first; b < end; ++b) {
    uvec4 info;
    uint calm;
    bool recent;
    if (computed(b, recentDue, stillBuild, info, calm, recent)) {
      if ((info.z & BODY_LARGE) == 0u) ++bodies;
      else ++larges;
      particles += info.y;
    } else if (recent) {
      recents += info.y;
    }
  }
  if (first < end) quietChunks[chunk] = bodies + particles == 0u ? 1u : 0u;
  // The recent sleepers' particles only sort into the grid, where their order does not matter:
  // a place for each thread's, in any order.
  uint nextRecent =
      recents == 0u ? 0u : atomicAdd(counters[COUNTER_RECENT_PARTICLES], recents);
  uint nextBody = bodies == 0u ? 0u : atomicAdd(counters[COUNTER_ACTIVE_BODIES], bodies);
  uint nextLarge = larges == 0u ? 0u : atomicAdd(counters[COUNTER_ACTIVE_LARGE], larges);
  uint nextParticle =
      particles == 0u ? 0u : atomicAdd(counters[COUNTER_ACTIVE_PARTICLES], particles);
  for (uint b = first; b < end && bodies + particles + recents > 0u; ++b) {
    uvec4 info;
    uint calm;
    bool recent;
    if (computed(b, recentDue, stillBuild, info, calm, recent)) {
      // A touched sleeper's mark is taken back: it is listed now.
      if (calm == calmTouched()) bodyVelocity[b].w = uintBitsToFloat(params.sleepSubsteps);
      if ((info.z & BODY_LARGE) == 0u) activeBodies[nextBody++] = b;
      else activeLargeBodies[nextLarge++] = info.z >> BODY_ENTRY_SHIFT;
      for (uint k = 0u; k < info.y; ++k) activeParticles[nextParticle++] = info.x + k;
    } else if (recent) {
      for (uint k = 0u; k < info.y; ++k) {
        activeParticles[params.particleCount - 1u - nextRecent++] = info.x + k;
      }
    } else {
      continue;
    }
    // Into this build's moving grid.
    if (requested != 0u) bodyGridBuild[b] = build;
  }
  // The last workgroup to get here sees every workgroup's totals.
  memoryBarrierBuffer();
  barrier();
  if (local == 0u) {
    uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    if (atomicAdd(counters[COUNTER_ACTIVE_GROUPS_DONE], 1u) == groups - 1u) {
      uint particles = atomicExchange(counters[COUNTER_ACTIVE_PARTICLES], 0u);
      writeCommand(ACTIVE_PASS_CONTACTS, particles);
      writeCommand(ACTIVE_PASS_BODIES, atomicExchange(counters[COUNTER_ACTIVE_BODIES], 0u));
      // Only the length: the pass is not dispatched from a command (layout.glsl).
      activeListLength(ACTIVE_PASS_LARGE) = atomicExchange(counters[COUNTER_ACTIVE_LARGE], 0u);
      counters[COUNTER_ACTIVE_GROUPS_DONE] = 0u;
      if (sortRequested) {
        bool sorts = particles > 0u;
        if (sorts || counters[COUNTER_LIST_REQUESTED] != 0u) {
          counters[COUNTER_LIST_REQUESTED] = LIST_REQUEST_ALL;
        }
        writeSortCommands(sorts);
        counters[COUNTER_GRANULE_SORT] = 0u;
      }
      // What list_check.comp does without sleep.
      // (Sleep leaves the lists' near part unmarked.)
      clearRunningCommands(decideListBuild(false, particles,
                                           atomicExchange(counters[COUNTER_RECENT_PARTICLES], 0u)),
                           false);
    }
  }
}
