// The grid of the last list build (gpu_buffers.def, CELL_*), searched over the 27 cells around a
// cell (list_build.comp, contacts.comp beyond a list, spawn_check.comp). Without SLEEPING it is
// one grid of every particle. Under SLEEPING it is two grids, so that a build sorts what is
// awake and not the sleepers again:
// - the still grid holds the particles of every body that was not computed (asleep, static) at
//   the build that last built it (COUNTER_STILL_BUILD); it is built again only when the CPU asks
//   for a build, or when the sleepers in the last moving grid outnumbered its awake particles
//   and were more than a sixteenth of all (stillGridDue, common/list_decision.glsl);
// - the moving grid, built at every build, holds the rest: the active list's particles and the
//   recent sleepers', those of bodies that were computed at some build since the still grid was
//   built (bodyGridBuild: the last build that put the body in the moving grid).
// A particle of the still grid counts only while its body's bodyGridBuild is older than the
// still grid, so the two never hold a particle twice and a search finds what one grid of every
// particle would: the lists, and every bit of the result, are the same. The two grids share the
// table's buckets and each search: a row's slots in both come from one cellStart lookup per end.
// A particle is in its grid where its listOrigin says (grid_count.comp), at most half the skin
// from where it is. The includer declares CELL_START_TEXTURE, CELL_PARTICLES_TEXTURE, COUNTERS
// and, under SLEEPING, BODY_GRID_BUILD_TEXTURE, and includes spatial_hash.glsl. A search reads
// the grid's multipliers once (hashMultipliers, common/grid_fit.glsl).
#include "grid_fit.glsl"

// The build that last built the still grid, 0 without SLEEPING (read once per search).
uint stillGridBuild() {
#ifdef SLEEPING
  return counters[COUNTER_STILL_BUILD];
#else
  return 0u;
#endif
}

// A grid is scanned as 9 rows of three x-neighbour cells around a cell: one range of consecutive
// buckets per row unless the row wraps around the table, then three.
uint rowParts(ivec3 cell, int row, uvec2 multipliers) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1), multipliers);
  return ((centre - 1u) & params.hashMask) < ((centre + 1u) & params.hashMask) ? 1u : 3u;
}

// The cellParticles slots of part `part` of row `row` (see rowParts): x, y the moving grid's
// [begin, end) (the one grid's without SLEEPING), z, w the still grid's (empty without).
uvec4 rowSlots(ivec3 cell, int row, uint part, uint parts, uvec2 multipliers) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1), multipliers);
  uint first =
      parts == 1u ? (centre - 1u) & params.hashMask : (centre + part - 1u) & params.hashMask;
  uint last = parts == 1u ? (centre + 1u) & params.hashMask : first;
  uvec4 slots = uvec4(texelFetch(cellStartTexture, int(first)).x,
                      texelFetch(cellStartTexture, int(last + 1u)).x, 0u, 0u);
#ifdef SLEEPING
  uint still = params.hashSize + 1u;
  slots.zw = params.particleCount + uvec2(texelFetch(cellStartTexture, int(still + first)).x,
                                          texelFetch(cellStartTexture, int(still + last + 1u)).x);
#endif
  return slots;
}

// The entries of a row's slots, in both grids.
uint rowEntries(uvec4 slots) {
  return slots.y - slots.x + slots.w - slots.z;
}

// The particle of entry k (below rowEntries) of a row's slots.
uint rowParticle(uvec4 slots, uint k) {
  uint moving = slots.y - slots.x;
  return texelFetch(cellParticlesTexture, int(k < moving ? slots.x + k : slots.z + k - moving)).x;
}

// Whether entry k of a row's slots, a particle of `body`, is in the grids (the still grid's
// entries of bodies the moving grid has taken since are not; `stillBuild`: stillGridBuild()).
bool rowHolds(uvec4 slots, uint k, uint body, uint stillBuild) {
#ifdef SLEEPING
  return k < slots.y - slots.x || texelFetch(bodyGridBuildTexture, int(body)).x < stillBuild;
#else
  return true;
#endif
}
