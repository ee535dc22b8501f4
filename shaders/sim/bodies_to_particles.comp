#version 450
// Particles of bodies the CPU has just set (added, moved by World::setBodyState, restored,
// copied by World::reserve): their state from the body's pose (paper eq. 7, 8). Not a pass of
// every substep: the integration passes write the particles of the bodies they move.
#include "common/layout.glsl"
#include "common/quaternion.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;

BODY_POSITION_TEXTURE
BODY_ORIENTATION_TEXTURE
BODY_VELOCITY_TEXTURE
BODY_ANGULAR_VELOCITY_TEXTURE
BODY_INFO_TEXTURE
PARTICLE_LOCAL_TEXTURE
PARTICLE_BODY_TEXTURE
LIST_ORIGIN_TEXTURE
#ifndef SLEEPING
LIST_NEAR_TEXTURE
#endif
PARTICLE_POSITION(writeonly)
PARTICLE_VELOCITY(writeonly)
COUNTERS(coherent)
#if !defined(PAPER_LAW) && defined(SLEEPING)
PARTICLE_SPIN(writeonly)
#endif

#include "common/particle_state.glsl"

// The first particle and how many.
layout(location = 0) uniform uvec2 range;

void main() {
  uint t = threadIndex();
  if (t >= range.y) return;
  uint i = range.x + t;
  uint body = texelFetch(particleBodyTexture, int(i)).x;
  // A dead body's particles leave the lists at the next build, which every change of the bodies
  // asks for; their state is never read.
  uint flags = texelFetch(bodyInfoTexture, int(body)).z;
  if ((flags & BODY_ALIVE) == 0u) return;
  vec4 velocity = texelFetch(bodyVelocityTexture, int(body));
  // Immovable bodies never hold a neighbour awake; the others as their count says (the CPU sets
  // it for a body it places: World::Impl::placedCalm).
  uint calm = 0u;
#ifdef SLEEPING
  uint motion = (flags & BODY_MOTION_MASK) >> BODY_MOTION_SHIFT;
  // A touched sleeper's mark is not copied (layout.glsl, "Sleep").
  calm = motion == MOTION_STATIC ? CALM_UNBOUNDED
                                 : min(floatBitsToUint(velocity.w), params.sleepSubsteps);
#endif
  storeParticle(i, texelFetch(particleLocalTexture, int(i)), body,
                texelFetch(bodyPositionTexture, int(body)).xyz,
                texelFetch(bodyOrientationTexture, int(body)), velocity.xyz,
                texelFetch(bodyAngularVelocityTexture, int(body)).xyz, calm);
}
