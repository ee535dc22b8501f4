// Neighbour lists (gpu_buffers.def, NEIGHBOUR_LIST, LIST_ORIGIN): each particle that needs forces
// lists the particles of other bodies closer than d + skin at the last build, ascending by id. A
// particle's contacts are then evaluated in partner-id order whenever the lists were built: the
// skin and the moments of the builds change no bit of the result, and the lists are a cache that
// snapshots need not carry. The lists are built from the grid of the build (common/grid.glsl).

// Entry k of particle i's list in neighbourList.
int listEntry(uint particle, uint k) {
  return int(k * params.listStride + particle);
}
