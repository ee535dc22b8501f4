#version 450
// Colliders in a neutral material. A cutaway surface hides the side that faces the eye, so that
// a cylinder wall or a container box shows the sand inside; it casts no shadow either, since a
// shadow of a wall the picture leaves out would only darken the sand for no visible reason. A
// one-sided surface (a plane) shows only its free side: an eye inside the solid sees through it.
#include "common/frame.glsl"

in vec3 vWorld;
in vec3 vNormal;
flat in float vCutaway;

#ifndef SHADOW_PASS
#include "common/lighting.glsl"
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
  writeShaded(pow(vec3(0.55, 0.56, 0.58), vec3(2.2)), vWorld, n);
#endif
}
