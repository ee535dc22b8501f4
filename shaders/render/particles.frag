#version 450
// Ray-cast sphere: exact silhouette, normal and depth, so that spheres intersect correctly with
// each other and with meshes. SHADOW_PASS: depth only, from the light.
#include "common/frame.glsl"

flat in vec3 vCentre;
flat in vec3 vAlbedo;
in vec3 vPosition;

#ifndef SHADOW_PASS
#include "common/lighting.glsl"
#endif

void main() {
  float r = params.x;
  vec3 origin = orthographicPass() ? vec3(vPosition.xy, 0.0) : vec3(0.0);
  vec3 direction = orthographicPass() ? vec3(0.0, 0.0, -1.0) : normalize(vPosition);
  vec3 oc = origin - vCentre;
  float b = dot(oc, direction);
  float c = dot(oc, oc) - r * r;
  float h = b * b - c;
  if (h < 0.0) discard;
  float t = -b - sqrt(h);
  vec3 hit = origin + t * direction;
  vec4 clip = projection * vec4(hit, 1.0);
  gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
#ifndef SHADOW_PASS
  vec3 normal = (hit - vCentre) / r;
  vec3 worldNormal = normalize(mat3(inverseView) * normal);
  vec3 worldHit = (inverseView * vec4(hit, 1.0)).xyz;
  writeShaded(vAlbedo, worldHit, worldNormal);
#endif
}
