#pragma once

// Opt-in access to a World's OpenGL buffers, for renderers that draw straight from the
// simulation's memory. No GL header is needed: names are plain `unsigned` (GLuint).

#include <cstdint>

namespace sandphys {

class World;

/// bodyInfo.z flag: the body exists (a sink clears it; draw nothing of a dead body).
inline constexpr std::uint32_t kBodyFlagAlive = 1u;
/// bodyInfo.z flag: the body is a sand granule (else a rough floor or a sampled body).
inline constexpr std::uint32_t kBodyFlagGranule = 2u;
/// bodyInfo.z bits 4-5: Motion (0 dynamic, 1 kinematic, 2 static).
inline constexpr std::uint32_t kBodyMotionShift = 4u;

/// Names of the World's shader storage buffers a renderer needs, with the element counts in
/// use. Every buffer is std430, one element per body or per particle, indexed from 0; only the
/// first bodyCount / particleCount elements are meaningful (the rest is capacity). Bind them to
/// any binding point, read-only: the World rebinds its own before each step.
///
/// Lifetime: the names stay valid until World::reserve (which replaces the buffers) or the
/// World's destruction; fetch a fresh RenderBuffers each frame, it costs nothing. The contents
/// are those after the last completed World::step or substep (GL orders the renderer's reads
/// after the step's writes; call glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT) before drawing).
struct RenderBuffers {
  /// vec4 per body: xyz centre of mass (m, world); w inverse mass (1/kg, 0 if not dynamic).
  unsigned bodyPosition = 0;
  /// vec4 per body: unit quaternion (x, y, z, w) from the body's principal frame to the world.
  unsigned bodyOrientation = 0;
  /// uvec4 per body: x first particle, y particle count, z flags (kBodyFlag*; test them by mask:
  /// the high bits hold other data), w guard count.
  unsigned bodyInfo = 0;
  /// vec4 per body: xyz velocity (m/s); w the calm count (uint bits; WorldSettings::sleep): the
  /// body is asleep when it is at least sleepSubsteps.
  unsigned bodyVelocity = 0;
  /// uint per body: the id (BodyId::index) of the body in the slot. A sort of the granules by
  /// place (WorldSettings::sortInterval) moves a body's state and id to another slot, so what
  /// should stay with a body (its colour) follows the id, not the slot.
  unsigned bodyIds = 0;
  /// vec4 per particle: xyz centre in the body's principal frame (m); w inverse particle mass.
  /// World position = bodyPosition.xyz + rotate(bodyOrientation, particleLocal.xyz).
  unsigned particleLocal = 0;
  /// uint per particle: index of the owning body.
  unsigned particleBody = 0;
  /// vec4 per particle: xyz world position (m) computed at the start of the last substep (one
  /// substep behind the bodies, and undefined before the first step; the pose above is current).
  unsigned particlePosition = 0;
  /// Bodies in use (alive or not).
  std::uint32_t bodyCount = 0;
  /// Particles in use.
  std::uint32_t particleCount = 0;
  /// Every particle is a sphere of this diameter, m.
  float particleDiameter = 0.0f;
  /// The calm count at which a body sleeps (SleepModel::substeps); 0 without sleep.
  std::uint32_t sleepSubsteps = 0;
};

/// The buffers of `world`. Does not touch the GPU.
RenderBuffers renderBuffers(const World& world);

}  // namespace sandphys
