// The state a substep's contacts start from, particle by particle (paper eq. 7, 8): written where
// the body's pose is at hand (after its integration, or by bodies_to_particles.comp when the CPU
// set it), so that the next contacts read one fetch per partner. Every writer uses this function,
// `precise`, so that a particle's state is the same bits whichever pass wrote it. The includer
// declares PARTICLE_LOCAL_TEXTURE, LIST_ORIGIN_TEXTURE (and without sleep LIST_NEAR_TEXTURE),
// PARTICLE_POSITION, PARTICLE_VELOCITY, COUNTERS and, under HertzMindlin with SLEEPING,
// PARTICLE_SPIN (and includes quaternion.glsl).

// Particle `k` of body `body` (`local`: its particleLocal entry) at the body's centre `centre`,
// orientation `q`, velocity `v` and spin `omega`, whose calm count is `calm` (layout.glsl; 0
// without SLEEPING). Asks for a list build when the particle has
// moved more than half the skin since the last one: two particles that were not listed, farther
// apart than d + skin, cannot touch before; and without sleep for a marking of the lists' near
// part in the same way.
void storeParticle(uint k, vec4 local, uint body, vec3 centre, vec4 q, vec3 v, vec3 omega,
                   uint calm) {
  precise vec3 offset = quatRotate(q, local.xyz);
  precise vec3 position = centre + offset;
  precise vec3 velocity = v + cross(omega, offset);
  particlePosition[k] = vec4(position, uintBitsToFloat(body));
  particleVelocity[k] = vec4(velocity, local.w);
#if !defined(PAPER_LAW) && defined(SLEEPING)
  particleSpin[k] = vec4(omega, uintBitsToFloat(calm));
#endif
  vec3 moved = position - texelFetch(listOriginTexture, int(k)).xyz;
  // The same value from every writer: no atomic needed.
  if (dot(moved, moved) > params.listMoveSquared)
    counters[COUNTER_LIST_REQUESTED] = LIST_REQUEST_MOVED;
#ifndef SLEEPING
  // The same for the near part of the lists (list_near.comp).
  vec3 movedNear = position - texelFetch(listNearTexture, int(k)).xyz;
  if (dot(movedNear, movedNear) > params.nearMoveSquared) counters[COUNTER_NEAR_REQUESTED] = 1u;
#endif
}
