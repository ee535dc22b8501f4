#version 450
// Sort of the granules by place, last pass: the contact slots name their partner particles by
// index (common/contact_slots.glsl), and the partners have moved. One thread per particle in use
// renames each slot's partner to the same particle of the slot its body went to (bodyOrder.z).
#include "common/layout.glsl"
#include "common/contact_slots.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_INFO_TEXTURE
PARTICLE_BODY_TEXTURE
BODY_ORDER(readonly)
CONTACT_SLOTS_0(coherent)
CONTACT_SLOTS_1(coherent)
CONTACT_SLOTS_2(coherent)

uint movedKey(uint key) {
  if (key == SLOT_EMPTY || (key & SLOT_COLLIDER) != 0u) return key;
  uint partner = key - 1u;
  uint body = texelFetch(particleBodyTexture, int(partner)).x;
  uint to = bodyOrder[body].z;
  return particleSlotKey(texelFetch(bodyInfoTexture, int(to)).x + partner -
                         texelFetch(bodyInfoTexture, int(body)).x);
}

vec4 moved(vec4 slot) {
  return vec4(slot.xyz, uintBitsToFloat(movedKey(floatBitsToUint(slot.w))));
}

void main() {
  uint particle = threadIndex();
  if (particle >= params.particleCount) return;
  for (uint k = 0u; k < uint(CONTACT_SLOTS_PER_GROUP); ++k) {
    uint entry = particle * uint(CONTACT_SLOTS_PER_GROUP) + k;
    contactSlots0[entry] = moved(contactSlots0[entry]);
    contactSlots1[entry] = moved(contactSlots1[entry]);
    contactSlots2[entry] = moved(contactSlots2[entry]);
  }
}
