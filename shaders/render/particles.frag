#version 450
// Ray-cast sphere: exact silhouette, normal and depth, so that spheres intersect correctly with
// each other and with meshes. The ray comes from the pixel itself, so the same code serves point
// sprites and quads. SHADOW_PASS: depth only, from the light.
#include "common/frame.glsl"

flat in vec3 vCentre;
flat in vec3 vAlbedo;

#ifndef SHADOW_PASS
#include "common/lighting.glsl"
#endif

// The ray hits the sphere at or behind the sprite's own depth (its nearest point), which lets the
// depth test run before this shader where the implementation supports it.
layout(depth_greater) out float gl_FragDepth;

void main() {
  float r = params.x;
  vec2 ndc = gl_FragCoord.xy * viewport.zw * 2.0 - 1.0;
  vec4 onFarPlane = inverseProjection * vec4(ndc, 1.0, 1.0);
  vec3 pixel = onFarPlane.xyz / onFarPlane.w;
  vec3 origin = orthographicPass() ? vec3(pixel.xy, 0.0) : vec3(0.0);
  vec3 direction = orthographicPass() ? vec3(0.0, 0.0, -1.0) : normalize(pixel);
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
