#version 450
// Bodies' surfaces in their material's colour, lit and shadowed like the sand.
#include "common/frame.glsl"

in vec3 vWorld;
in vec3 vNormal;
flat in uint vMaterial;

#ifndef SHADOW_PASS
#include "common/lighting.glsl"

// Linear albedo of each scenes::BodyMaterial (RenderSettings::materialColours); the renderer
// defines BODY_MATERIALS, their count.
uniform vec3 materialAlbedo[BODY_MATERIALS];
#endif

void main() {
#ifndef SHADOW_PASS
  vec3 n = normalize(vNormal);
  // A mesh file's open or inward-wound triangles are lit on the side the eye sees.
  if (dot(n, cameraPosition.xyz - vWorld) < 0.0) n = -n;
  writeShaded(materialAlbedo[min(vMaterial, uint(BODY_MATERIALS) - 1u)], vWorld, n);
#endif
}
