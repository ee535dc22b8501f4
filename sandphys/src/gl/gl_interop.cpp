#include "sandphys/gl_interop.h"

#include "core/world_access.h"

namespace sandphys {

// The public flags are the layout's (layout.glsl, gpu_layout.h); a change there must show here.
static_assert(kBodyFlagAlive == detail::kBodyAlive);
static_assert(kBodyFlagGranule == detail::kBodyGranule);
static_assert(kBodyMotionShift == detail::kBodyMotionShift);

RenderBuffers renderBuffers(const World& world) {
  const World::Impl& w = detail::WorldAccess::impl(world);
  RenderBuffers b;
  b.bodyPosition = w.buffers[detail::kBodyPosition].id();
  b.bodyOrientation = w.buffers[detail::kBodyOrientation].id();
  b.bodyInfo = w.buffers[detail::kBodyInfo].id();
  b.bodyVelocity = w.buffers[detail::kBodyVelocity].id();
  b.bodyIds = w.buffers[detail::kBodyIds].id();
  b.particleLocal = w.buffers[detail::kParticleLocal].id();
  b.particleBody = w.buffers[detail::kParticleBody].id();
  b.particlePosition = w.buffers[detail::kParticlePosition].id();
  b.bodyCount = w.bodyCount;
  b.particleCount = w.particleCount;
  b.particleDiameter = w.settings.particleDiameter;
  b.sleepSubsteps = w.sleep.enabled ? w.sleep.substeps : 0u;
  return b;
}

}  // namespace sandphys
