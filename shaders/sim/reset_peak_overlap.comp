#version 450
// World::resetPeakOverlap, and World::step at the start of each frame: the largest overlap of
// every particle in use (particleStats.y) restarts at zero, so that WorldStats::maxOverlap reads
// the peak since then and reading it changes nothing. Not a pass of every substep.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_STATS(coherent)

void main() {
  uint i = threadIndex();
  if (i >= params.particleCount) return;
  particleStats[i].y = 0u;
}
