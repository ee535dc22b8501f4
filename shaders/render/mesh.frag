#version 450
// Colliders in a neutral material. A cutaway surface hides the side that faces the eye, so that
// a cylinder wall or a container box shows the sand inside; it casts no shadow either, since a
// shadow of a wall the picture leaves out would only darken the sand for no visible reason. A
// one-sided surface (a plane) shows only its free side: an eye inside the solid sees through it.
// Any surface that stands between the eye and the camera's focus is drawn see-through: a screen
// door that keeps one pixel in four, so the sand behind it shows and the wall is still seen.
#include "common/frame.glsl"

in vec3 vWorld;
in vec3 vNormal;
flat in float vCutaway;

#ifndef SHADOW_PASS
#include "common/lighting.glsl"

// The camera's focus box (world, m); focusMin.w is 0 without one.
uniform vec4 focusMin;
uniform vec3 focusMax;

// The surface at `p`, whose normal `n` faces the eye, has the focus box's centre behind it, and
// the line of sight through `p` meets the box only beyond `p`. (The first condition spares a
// floor seen at a grazing angle, whose lines of sight may dip into the box's lowest sliver.)
bool hidesFocus(vec3 p, vec3 n) {
  if (focusMin.w < 0.5) return false;
  if (dot(n, 0.5 * (focusMin.xyz + focusMax) - p) >= 0.0) return false;
  vec3 eye = cameraPosition.xyz;
  vec3 inverse = 1.0 / (p - eye);  // the eye at t = 0, p at t = 1
  vec3 t0 = (focusMin.xyz - eye) * inverse;
  vec3 t1 = (focusMax - eye) * inverse;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), near.z);
  float leave = min(min(far.x, far.y), far.z);
  return enter <= leave && enter > 1.0;
}
#endif

void main() {
#ifdef SHADOW_PASS
  if (vCutaway > 0.5 && vCutaway < 1.5) discard;
#else
  vec3 n = normalize(vNormal);
  vec3 toEye = cameraPosition.xyz - vWorld;
  bool facesEye = dot(n, toEye) > 0.0;
  if (vCutaway > 0.5 && vCutaway < 1.5 && facesEye) discard;
  if (vCutaway > 1.5 && !facesEye) discard;
  if (!facesEye) n = -n;  // seen from inside: light the inner face
  if (hidesFocus(vWorld, n) && ((int(gl_FragCoord.x) | int(gl_FragCoord.y)) & 1) != 0) discard;
  writeShaded(pow(vec3(0.55, 0.56, 0.58), vec3(2.2)), vWorld, n);
#endif
}
