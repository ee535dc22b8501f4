// The World's buffers as sandphys/gl_interop.h documents them (std430), read-only. The renderer
// binds them at these points; the simulation uses its own bindings.
layout(std430, binding = 0) readonly buffer BodyPositionBuffer { vec4 bodyPosition[]; };
layout(std430, binding = 1) readonly buffer BodyOrientationBuffer { vec4 bodyOrientation[]; };
layout(std430, binding = 2) readonly buffer BodyInfoBuffer { uvec4 bodyInfo[]; };
layout(std430, binding = 3) readonly buffer ParticleLocalBuffer { vec4 particleLocal[]; };
layout(std430, binding = 4) readonly buffer ParticleBodyBuffer { uint particleBody[]; };
// xyz: velocity; w: calm count (uint bits), asleep from RenderBuffers::sleepSubsteps on.
layout(std430, binding = 5) readonly buffer BodyVelocityBuffer { vec4 bodyVelocity[]; };
// The id of the body in each slot (RenderBuffers::bodyIds), which a sort of the granules moves.
layout(std430, binding = 7) readonly buffer BodyIdsBuffer { uint bodyIds[]; };

#define BODY_ALIVE 1u
#define BODY_GRANULE 2u

// Quaternion (x, y, z, w) rotation, as shaders/sim/common/quaternion.glsl.
vec3 rotateByQuat(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}
