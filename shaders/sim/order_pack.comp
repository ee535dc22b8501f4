#version 450
// Sort of the granules by place, the moves: one buffer at a time (bound as ORDER_TARGET), the
// words of each body or particle in use are copied out to the neighbour lists, which the sort
// leaves to the next build to fill, and order_gather.comp brings them back in their new places.
#include "common/layout.glsl"
#include "common/order_words.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

ORDER_TARGET(readonly)
NEIGHBOUR_LIST(writeonly)

void main() {
  uint item = threadIndex();
  if (item >= orderItems()) return;
  for (uint k = 0u; k < orderShape.w; ++k) {
    neighbourList[item * orderShape.w + k] = orderTarget[orderWord(item, k)];
  }
}
