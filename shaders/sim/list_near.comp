#version 450
// Pass 2b, without sleep: one thread per particle marks the entries of its list within
// d + near skin of where it stands (listNear, common/neighbour_list.glsl) and records that place,
// from which the integration measures how far it moves. Indirect: after every build, and when
// some particle moved more than half the near skin since the last marking (list_check.comp
// decides); zero groups otherwise.
#include "common/layout.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

PARTICLE_POSITION_TEXTURE
NEIGHBOUR_LIST_TEXTURE
LIST_ORIGIN_TEXTURE
LIST_NEAR(writeonly)
#include "common/neighbour_list.glsl"

void main() {
  uint i = threadIndex();
  if (i >= params.particleCount) return;
  vec3 self = texelFetch(particlePositionTexture, int(i)).xyz;
  uint listed = listCount(floatBitsToUint(texelFetch(listOriginTexture, int(i)).w));
  uint inList = listed == LIST_DEAD ? 0u : min(listed, uint(NEIGHBOUR_LIST_CAPACITY));
  uint near = 0u;
  for (uint k = 0u; k < inList; ++k) {
    uint partner = texelFetch(neighbourListTexture, listEntry(i, k)).x;
    vec3 d = self - texelFetch(particlePositionTexture, int(partner)).xyz;
    if (dot(d, d) < params.nearReachSquared) near |= 1u << k;
  }
  listNear[i] = vec4(self, uintBitsToFloat(near));
}
