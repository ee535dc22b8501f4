#version 450
// Bodies drawn as their surfaces (samples/render/surface_mesh.cpp): each vertex is given in its
// body's principal frame and placed by the pose the World holds on the GPU now, so a surface
// moves with its body without a read-back. A dead body's triangles collapse to a point outside
// the view and are dropped.
#include "common/frame.glsl"
#include "common/world_buffers.glsl"

layout(location = 0) in vec3 inPosition;  // principal frame, about the centre of mass (m)
layout(location = 1) in uint inBody;      // body slot
layout(location = 2) in vec3 inNormal;    // outward, principal frame
layout(location = 3) in uint inMaterial;  // scenes::BodyMaterial

out vec3 vWorld;
out vec3 vNormal;
flat out uint vMaterial;

void main() {
  vec4 q = bodyOrientation[inBody];
  vWorld = bodyPosition[inBody].xyz + rotateByQuat(q, inPosition);
  vNormal = rotateByQuat(q, inNormal);
  vMaterial = inMaterial;
  gl_Position = projection * view * vec4(vWorld, 1.0);
  if ((bodyInfo[inBody].z & BODY_ALIVE) == 0u) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
