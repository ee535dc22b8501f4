// Neighbour lists (layout.glsl, NEIGHBOUR_LIST, LIST_ORIGIN): each particle that needs forces lists
// the particles of other bodies closer than d + skin at the last build, ascending by id. A
// particle's contacts are then evaluated in partner-id order whenever the lists were built: the
// skin and the moments of the builds change no bit of the result, and the lists are a cache that
// snapshots need not carry. The includer declares CELL_START_TEXTURE and CELL_PARTICLES_TEXTURE
// and includes spatial_hash.glsl.

// Entry k of particle i's list in neighbourList.
int listEntry(uint particle, uint k) {
  return int(k * listLayout.x + particle);
}

// The grids of the last build: one, or under SLEEPING the moving grid (0) and the still grid (1,
// layout.glsl "Sleep"; the includer then also declares STILL_CELL_START_TEXTURE,
// STILL_CELL_PARTICLES_TEXTURE, BODY_GRID_BUILD_TEXTURE and COUNTERS). A search visits both and
// takes a particle of the still grid only where gridHolds says so.
#ifdef SLEEPING
#define GRIDS 2u
#define stillGridBuild() counters[COUNTER_STILL_BUILD]
#else
#define GRIDS 1u
#define stillGridBuild() 0u
#endif

uint gridCellStart(uint grid, uint bucket) {
#ifdef SLEEPING
  if (grid == 1u) return texelFetch(stillCellStartTexture, int(bucket)).x;
#endif
  return texelFetch(cellStartTexture, int(bucket)).x;
}

// The particle in slot `slot` of `grid`.
uint gridParticleAt(uint grid, uint slot) {
#ifdef SLEEPING
  if (grid == 1u) return texelFetch(stillCellParticlesTexture, int(slot)).x;
#endif
  return texelFetch(cellParticlesTexture, int(slot)).x;
}

// Whether a particle of `body` found in `grid` is there: in the still grid only while the body
// has not gone into the moving grid since the still grid was built (`stillBuild`,
// COUNTER_STILL_BUILD).
bool gridHolds(uint grid, uint body, uint stillBuild) {
#ifdef SLEEPING
  return grid == 0u || texelFetch(bodyGridBuildTexture, int(body)).x < stillBuild;
#else
  return true;
#endif
}

// A grid is scanned as 9 rows of three x-neighbour cells around a cell: one range of consecutive
// buckets per row unless the row wraps around the table, then three.
uint rowParts(ivec3 cell, int row) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1));
  return ((centre - 1u) & counts.z) < ((centre + 1u) & counts.z) ? 1u : 3u;
}

// [begin, end) of the bucket-ordered slots of part `part` of row `row` (see rowParts) in `grid`.
uvec2 rowSlots(uint grid, ivec3 cell, int row, uint part, uint parts) {
  uint centre = bucketOf(cell + ivec3(0, row % 3 - 1, row / 3 - 1));
  uint first = parts == 1u ? (centre - 1u) & counts.z : (centre + part - 1u) & counts.z;
  uint last = parts == 1u ? (centre + 1u) & counts.z : first;
  return uvec2(gridCellStart(grid, first), gridCellStart(grid, last + 1u));
}
