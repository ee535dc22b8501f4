#version 450
// Sphere impostors straight from the World's buffers: six vertices per particle, no vertex
// attributes. The quad lies in the plane perpendicular to the line of sight through the centre,
// one radius in front of it, where a square of half-side r covers the sphere's whole silhouette
// under perspective (the tangent cone is narrower than r there) and exactly under orthography.
#include "common/frame.glsl"
#include "common/world_buffers.glsl"

flat out vec3 vCentre;  // view space
flat out vec3 vAlbedo;
out vec3 vPosition;     // view space, on the quad

// Integer hash (a variant of Wang's) for per-granule colour: stable for a body's lifetime.
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

const vec2 kCorners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1),
                                vec2(-1, 1));

void main() {
  uint particle = uint(gl_VertexID) / 6u;
  vec2 corner = kCorners[uint(gl_VertexID) % 6u];
  uint body = particleBody[particle];
  uvec4 info = bodyInfo[body];
  if ((info.z & BODY_ALIVE) == 0u) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: dropped
    return;
  }
  vec3 world = bodyPosition[body].xyz + rotateByQuat(bodyOrientation[body], particleLocal[particle].xyz);
  float r = params.x;
  vec3 centre = (view * vec4(world, 1.0)).xyz;
  vec3 w = orthographicPass() ? vec3(0.0, 0.0, -1.0) : normalize(centre);
  vec3 helper = abs(w.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 u = normalize(cross(w, helper));
  vec3 v = cross(u, w);
  vec3 position = centre - w * r + (corner.x * u + corner.y * v) * r;
  vCentre = centre;
  vPosition = position;
  // Rough floors and sampled bodies are not sand: a neutral stone colour.
  vAlbedo = (info.z & BODY_GRANULE) != 0u ? granuleAlbedo(body) : pow(vec3(0.45, 0.43, 0.40), vec3(2.2));
  gl_Position = projection * vec4(position, 1.0);
}
