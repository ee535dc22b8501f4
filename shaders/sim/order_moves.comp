#version 450
// Sort of the granules by place, pass 4: the n-th slot of a sorted granule takes the n-th granule
// of the grid's order. Each slot learns where its new state comes from (bodyOrder.y) and each
// granule where it goes (bodyOrder.z); every other slot keeps its own. Should the two counts
// differ (a granule missing from the grid), every slot keeps its own: no sort rather than a wrong
// one.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

CELL_START_TEXTURE
CELL_COUNT(coherent)
BODY_ORDER(coherent)
COUNTERS(readonly)

void main() {
  uint slot = threadIndex();
  if (slot >= params.bodyCount) return;
  bool sorted = cellCount[slot] != 0u;
  cellCount[slot] = 0u;
  uint slots = texelFetch(cellStartTexture, int(params.hashSize)).x;
  if (sorted && slots == counters[COUNTER_ORDER_SEQUENCE]) {
    uint source = bodyOrder[texelFetch(cellStartTexture, int(slot)).x].x;
    bodyOrder[slot].y = source;
    bodyOrder[source].z = slot;
  } else {
    bodyOrder[slot].y = slot;
    bodyOrder[slot].z = slot;
  }
}
