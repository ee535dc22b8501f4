// The sort of the granules by place (WorldSettings::sortInterval; docs/architecture.md, "Granule
// order"): which bodies it moves, and the one buffer its moves copy at a time.

// Every granule that moves freely and is alive: they all have the World's granule template, so
// their slots can trade states.
bool sortsGranule(uint flags) {
  uint motion = (flags & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  return (flags & (BODY_ALIVE | BODY_GRANULE)) == (BODY_ALIVE | BODY_GRANULE) &&
         motion == MOTION_DYNAMIC;
}

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
