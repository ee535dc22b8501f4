#version 450
// Sort of the granules by place, the moves (order_pack.comp): each body or particle in use takes
// the words of the one whose state comes to its slot (bodyOrder.y), from the copy.
#include "common/layout.glsl"
#include "common/order_words.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_INFO_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_ORDER(readonly)
NEIGHBOUR_LIST(readonly)
ORDER_TARGET(writeonly)

void main() {
  uint item = threadIndex();
  if (item >= orderItems()) return;
  uint source;
  if (orderShape.x == ORDER_BODIES) {
    source = bodyOrder[item].y;
  } else {
    // A particle takes the same particle of the body whose state comes to its body's slot (every
    // granule the sort moves has the World's granule template).
    uint body = texelFetch(particleBodyTexture, int(item)).x;
    uint from = bodyOrder[body].y;
    uint first = texelFetch(bodyInfoTexture, int(body)).x;
    source = texelFetch(bodyInfoTexture, int(from)).x + item - first;
  }
  for (uint k = 0u; k < orderShape.w; ++k) {
    orderTarget[orderWord(item, k)] = neighbourList[source * orderShape.w + k];
  }
}
