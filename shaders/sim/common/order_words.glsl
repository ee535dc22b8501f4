// The sort of the granules by place (common/granule_order.glsl): the one buffer its moves
// (order_pack.comp, order_gather.comp) copy at a time, bound as ORDER_TARGET.

#define ORDER_BODIES 0u
#define ORDER_PARTICLES 1u
// x: ORDER_BODIES or ORDER_PARTICLES (what one item is); y: words per item in the buffer; z: the
// first word of an item that moves; w: how many words from there.
layout(location = 0) uniform uvec4 orderShape;

uint orderItems() {
  return orderShape.x == ORDER_BODIES ? params.bodyCount : params.particleCount;
}

uint orderWord(uint item, uint k) {
  return item * orderShape.y + orderShape.z + k;
}
