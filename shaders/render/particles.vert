#version 450
// Sphere impostors straight from the World's buffers, with no vertex attributes. Two shapes:
// POINT_SPRITES: one vertex per particle, a point sprite whose square covers the sphere's exact
// screen-space bounds (tangent lines per axis). One vertex instead of six matters on Mesa's
// llvmpipe, where vertex work does not spread over the CPU's cores as pixel work does. A point
// is limited to maxPointSize pixels, so particles that would need more are dropped here and
// drawn by the quad shape in a second draw (only issued when the camera is that close).
// Otherwise: six vertices per particle, a quad in the plane perpendicular to the line of sight
// through the centre, one radius in front of it, where a square of half-side r covers the
// sphere's whole silhouette under perspective and exactly under orthography; with POINT_SPRITES
// off it draws only the particles too large for a point.
#include "common/frame.glsl"
#include "common/world_buffers.glsl"

flat out vec3 vCentre;  // view space
flat out vec3 vAlbedo;

// Integer hash (a variant of Wang's) for per-granule colour: of the body's id, so stable for its
// lifetime, wherever a sort of the granules puts it.
uint hashUint(uint x) {
  x = (x ^ 61u) ^ (x >> 16);
  x *= 9u;
  x ^= x >> 4;
  x *= 0x27d4eb2du;
  x ^= x >> 15;
  return x;
}

vec3 granuleAlbedo(uint body) {
  uint h = hashUint(body);
  float a = float(h & 1023u) / 1023.0;
  float b = float((h >> 10) & 1023u) / 1023.0;
  float c = float((h >> 20) & 1023u) / 1023.0;
  // Quartz-like tan grains from pale to ochre, and a few darker lithic grains, as in real sand.
  vec3 pale = vec3(0.80, 0.68, 0.50);
  vec3 ochre = vec3(0.66, 0.47, 0.27);
  vec3 colour = mix(pale, ochre, a) * (0.85 + 0.3 * b);
  if (c < 0.06) colour = vec3(0.30, 0.27, 0.24) * (0.8 + 4.0 * c);
  // The albedo is given in sRGB-ish terms above; light in linear space.
  return pow(colour, vec3(2.2));
}

// Bodies drawn as their surfaces instead (surface.vert): bit b % 32 of word b / 32 is set for
// body b; bodies from surfaceBodyWords * 32 on have none.
layout(std430, binding = 6) readonly buffer SurfaceBodyBuffer { uint surfaceBodies[]; };
uniform uint surfaceBodyWords;

uniform float maxPointSize;  // px, GL_POINT_SIZE_RANGE's upper end
// Granules whose calm count is at least this are asleep and tinted (0: no tint).
uniform uint asleepFrom;

// Screen-space bounds of the sphere along one axis, as tangents of the angle from the line of
// sight: the tangent lines from the eye to the circle (a, depth) of radius r in that axis's
// plane. Returns (lo, hi); huge when the eye is inside or the sphere reaches behind the eye.
vec2 tangentBounds(float a, float depth, float r) {
  float l2 = a * a + depth * depth;
  // depth > r keeps both tangents short of the image plane (angles under 90 degrees).
  if (l2 <= r * r * 1.0001 || depth <= r) return vec2(-1e6, 1e6);
  float t = sqrt(l2 - r * r);
  // tan(phi -/+ alpha) with tan(phi) = a/depth, tan(alpha) = r/t.
  float lo = (a * t - r * depth) / (depth * t + a * r);
  float hi = (a * t + r * depth) / (depth * t - a * r);
  return vec2(lo, hi);
}

// Side of the square (px) that covers the sphere at view-space `centre`, and its centre (NDC).
float spriteSize(vec3 centre, float r, out vec2 ndcCentre) {
  if (orthographicPass()) {
    vec4 clip = projection * vec4(centre, 1.0);
    ndcCentre = clip.xy / clip.w;
    return 2.0 * r * max(projection[0][0] * viewport.x, projection[1][1] * viewport.y) * 0.5;
  }
  float depth = -centre.z;
  vec2 bx = tangentBounds(centre.x, depth, r) * projection[0][0];
  vec2 by = tangentBounds(centre.y, depth, r) * projection[1][1];
  ndcCentre = vec2(bx.x + bx.y, by.x + by.y) * 0.5;
  return max((bx.y - bx.x) * viewport.x, (by.y - by.x) * viewport.y) * 0.5;
}

#ifndef POINT_SPRITES
const vec2 kCorners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1),
                                vec2(-1, 1));
#endif

void main() {
#ifdef POINT_SPRITES
  uint particle = uint(gl_VertexID);
#else
  uint particle = uint(gl_VertexID) / 6u;
  vec2 corner = kCorners[uint(gl_VertexID) % 6u];
#endif
  uint body = particleBody[particle];
  uvec4 info = bodyInfo[body];
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: dropped
  if ((info.z & BODY_ALIVE) == 0u) return;
  if (body / 32u < surfaceBodyWords && (surfaceBodies[body / 32u] & (1u << (body % 32u))) != 0u) {
    return;
  }
  vec3 world = bodyPosition[body].xyz + rotateByQuat(bodyOrientation[body], particleLocal[particle].xyz);
  float r = params.x;
  vec3 centre = (view * vec4(world, 1.0)).xyz;
  vec2 ndcCentre;
  // One pixel of margin for rasterisation at the square's edge.
  float size = spriteSize(centre, r, ndcCentre) + 1.0;
  bool fitsPoint = size <= maxPointSize;
  vCentre = centre;
  // Rough floors and sampled bodies are not sand: a neutral stone colour.
  vAlbedo = (info.z & BODY_GRANULE) != 0u ? granuleAlbedo(bodyIds[body]) : pow(vec3(0.45, 0.43, 0.40), vec3(2.2));
#ifndef SHADOW_PASS
  if (asleepFrom != 0u && (info.z & BODY_GRANULE) != 0u &&
      floatBitsToUint(bodyVelocity[body].w) >= asleepFrom) {
    vAlbedo = mix(vAlbedo, pow(vec3(0.35, 0.45, 0.65), vec3(2.2)), 0.6);
  }
#endif
#ifdef POINT_SPRITES
  if (!fitsPoint) return;
  // The point's depth is the sphere's nearest point on the line of sight (clamped into the view
  // volume so that a grain cut by the near plane is still drawn); the fragments write their own.
  vec3 front = orthographicPass() ? centre + vec3(0.0, 0.0, r) : centre - normalize(centre) * r;
  vec4 frontClip = projection * vec4(front, 1.0);
  float z = clamp(frontClip.z / max(frontClip.w, 1e-6), -1.0, 1.0);
  gl_Position = vec4(ndcCentre, z, 1.0);
  gl_PointSize = size;
#else
  if (fitsPoint) return;
  vec3 w = orthographicPass() ? vec3(0.0, 0.0, -1.0) : normalize(centre);
  vec3 helper = abs(w.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(w, helper));
  vec3 v = cross(u, w);
  vec3 position = centre - w * r + (corner.x * u + corner.y * v) * r;
  gl_Position = projection * vec4(position, 1.0);
#endif
}
