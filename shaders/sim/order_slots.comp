#version 450
// Sort of the granules by place, pass 3: the slots the sorted granules fill are those they hold,
// in ascending order. One thread per body slot marks, in cellCount, the slots of granules the sort
// moves; the scan after it numbers them.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_INFO_TEXTURE
CELL_COUNT(writeonly)
#ifdef SLEEPING
BODY_GRID_BUILD_TEXTURE
COUNTERS(readonly)
#endif
#include "common/granule_order.glsl"

void main() {
  uint slot = threadIndex();
  if (slot >= params.bodyCount) return;
  if (sortsGranule(slot)) cellCount[slot] = 1u;
}
