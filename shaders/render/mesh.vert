#version 450
// Collider meshes built on the CPU (samples/render/collider_mesh.cpp): position, outward normal
// and a cutaway flag (thin walls and containers, whose side facing the eye is not drawn).
#include "common/frame.glsl"

layout(location = 0) in vec4 inPosition;  // xyz world; w: 1 = cutaway, 2 = one-sided
layout(location = 1) in vec4 inNormal;    // xyz outward normal (world)

out vec3 vWorld;
out vec3 vNormal;
flat out float vCutaway;

void main() {
  vWorld = inPosition.xyz;
  vNormal = inNormal.xyz;
  vCutaway = inPosition.w;
  gl_Position = projection * view * vec4(inPosition.xyz, 1.0);
}
