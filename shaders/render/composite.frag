#version 450
// Ambient occlusion and final colour. Screen-space AO over the scene pass's depth and normals:
// points of a hemisphere around each surface point that lie behind the depth buffer are
// occluded. Two radii: about a grain (the crevices between grains, which make sand look
// granular) and several grains (the foot of a pile and the corner with the floor, which make a
// pile read as a heap). The result scales the hemisphere ambient only; direct light keeps its
// shadow map. Writes sRGB colour and the scene's depth into the bound framebuffer.
#include "common/frame.glsl"

layout(binding = 1) uniform sampler2D directTexture;
layout(binding = 2) uniform sampler2D ambientTexture;
layout(binding = 3) uniform sampler2D normalTexture;
layout(binding = 4) uniform sampler2D depthTexture;

uniform int aoSamples;     // 0 turns AO off
uniform vec3 background;  // sRGB, where nothing was drawn

in vec2 vUv;
layout(location = 0) out vec4 outColour;

vec3 viewPositionAt(vec2 uv, float depth) {
  vec4 ndc = vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  vec4 p = inverseProjection * ndc;
  return p.xyz / p.w;
}

// Interleaved gradient noise (Jimenez 2014): decorrelates the sample pattern between pixels.
float noise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

float occlusion(vec3 p, vec3 n, float radius, float angleOffset) {
  // A tangent frame around n; samples on a spiral in the hemisphere, at growing distances.
  vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = normalize(cross(helper, n));
  vec3 bt = cross(n, t);
  float occluded = 0.0;
  for (int i = 0; i < aoSamples; ++i) {
    float f = (float(i) + 0.5) / float(aoSamples);
    float angle = 2.39996323 * float(i) + angleOffset * 6.2831853;
    float s = radius * mix(0.15, 1.0, f * f);
    float elevation = 0.2 + 0.8 * fract(f * 7.0 + angleOffset);
    vec3 dir = normalize(cos(angle) * t + sin(angle) * bt + elevation * n);
    vec3 q = p + dir * s;
    vec4 clip = projection * vec4(q, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
    float sceneDepth = texture(depthTexture, uv).r;
    if (sceneDepth >= 1.0) continue;
    vec3 scene = viewPositionAt(uv, sceneDepth);
    // Occluded when the surface there is in front of the sample point; ignore surfaces far in
    // front (a different object), which would draw dark halos.
    float inFront = scene.z - q.z;
    if (inFront > 0.02 * radius) occluded += smoothstep(0.0, 1.0, radius / max(inFront, 1e-6) - 0.5);
  }
  return 1.0 - occluded / float(max(aoSamples, 1));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(depthTexture, pixel, 0).r;
  if (depth >= 1.0) {
    outColour = vec4(background, 1.0);
    gl_FragDepth = 1.0;
    return;
  }
  vec3 direct = texelFetch(directTexture, pixel, 0).rgb;
  vec3 ambient = texelFetch(ambientTexture, pixel, 0).rgb;
  float ao = 1.0;
  if (aoSamples > 0) {
    vec3 p = viewPositionAt(vUv, depth);
    vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * 2.0 - 1.0);
    float jitter = noise(gl_FragCoord.xy);
    float fine = occlusion(p + n * 0.02 * params.w, n, params.w, jitter);
    float coarse = occlusion(p + n * 0.02 * params.w, n, 6.0 * params.w, jitter + 0.37);
    ao = fine * mix(1.0, coarse, 0.8);
  }
  vec3 colour = direct + ambient * ao;
  // Simple filmic shoulder, then sRGB-like encoding.
  colour = colour / (1.0 + 0.15 * colour);
  outColour = vec4(pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
  gl_FragDepth = depth;
}
