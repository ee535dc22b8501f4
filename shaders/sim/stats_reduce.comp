#version 450
// Statistics, once per frame (never per substep): a fixed number of workgroups each reduce a
// fixed stride of particles and bodies in shared memory in a fixed order; the CPU adds the
// partials in double. Reads only, through the views: the largest overlap restarts in
// reset_peak_overlap.comp.
#include "common/layout.glsl"

#define STATS_THREADS 256
layout(local_size_x = STATS_THREADS) in;

PARTICLE_STATS_TEXTURE
BODY_VELOCITY_TEXTURE
BODY_ANGULAR_VELOCITY_TEXTURE
BODY_ORIENTATION_TEXTURE
BODY_INERTIA_TEXTURE
BODY_INFO_TEXTURE
STATS_PARTIALS(writeonly)
#ifdef SLEEPING
LIST_ORIGIN_TEXTURE
#endif

#include "common/quaternion.glsl"

shared uvec4 sharedCounts[STATS_THREADS];
shared vec4 sharedSums[STATS_THREADS];
shared uint sharedAsleep[STATS_THREADS];

void main() {
  uint local = gl_LocalInvocationID.x;
  uint stride = gl_NumWorkGroups.x * STATS_THREADS;
  uvec4 c = uvec4(0u);
  vec4 s = vec4(0.0);
  uint asleep = 0u;
  for (uint i = gl_GlobalInvocationID.x; i < params.particleCount; i += stride) {
    uvec4 p = texelFetch(particleStatsTexture, int(i));
#ifdef SLEEPING
    // Only active particles are computed, so a dead body's particles keep their last contacts.
    if (floatBitsToUint(texelFetch(listOriginTexture, int(i)).w) == LIST_DEAD) p.xw = uvec2(0u);
#endif
    c.x += p.x;
    c.y += p.w;
    c.z += p.z;
    s.z = max(s.z, uintBitsToFloat(p.y));
  }
  for (uint b = gl_GlobalInvocationID.x; b < params.bodyCount; b += stride) {
    uvec4 info = texelFetch(bodyInfoTexture, int(b));
    c.w += info.w;
    if ((info.z & BODY_ALIVE) == 0u) continue;
    vec4 velocity = texelFetch(bodyVelocityTexture, int(b));
    if ((info.z & BODY_GRANULE) != 0u) {
      s.w += 1.0;
#ifdef SLEEPING
      if (floatBitsToUint(velocity.w) >= params.sleepSubsteps) ++asleep;
#endif
    }
    if (((info.z & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT) != MOTION_DYNAMIC) continue;
    vec4 inertia = texelFetch(bodyInertiaTexture, int(b));
    vec3 v = velocity.xyz;
    vec3 omegaLocal = quatRotateInverse(texelFetch(bodyOrientationTexture, int(b)),
                                        texelFetch(bodyAngularVelocityTexture, int(b)).xyz);
    s.x += 0.5 * inertia.w * dot(v, v);
    s.y += 0.5 * dot(omegaLocal, inertia.xyz * omegaLocal);
  }
  sharedCounts[local] = c;
  sharedSums[local] = s;
  sharedAsleep[local] = asleep;
  barrier();
  for (uint width = STATS_THREADS / 2u; width > 0u; width >>= 1u) {
    if (local < width) {
      sharedCounts[local] += sharedCounts[local + width];
      vec4 a = sharedSums[local];
      vec4 o = sharedSums[local + width];
      sharedSums[local] = vec4(a.xy + o.xy, max(a.z, o.z), a.w + o.w);
      sharedAsleep[local] += sharedAsleep[local + width];
    }
    barrier();
  }
  if (local == 0u) {
    statsPartials[gl_WorkGroupID.x].counts = sharedCounts[0];
    statsPartials[gl_WorkGroupID.x].sums = sharedSums[0];
    statsPartials[gl_WorkGroupID.x].sleep = uvec4(sharedAsleep[0], 0u, 0u, 0u);
  }
}
