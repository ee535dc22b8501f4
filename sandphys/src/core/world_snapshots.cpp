// Putting a World back to a snapshot (World::restoreSnapshot); taking one is in world_readback.cpp.
#include "sandphys/world.h"

#include <bit>
#include <vector>

#include "core/contact_state.h"
#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"
#include "gl/gl_check.h"

namespace sandphys {

using namespace detail;

void World::restoreSnapshot(const WorldSnapshot& snapshot) {
  Impl& w = impl();
  const auto slots = static_cast<std::uint32_t>(snapshot.bodies.size());
  require(slots <= w.bodyCount, "WorldSnapshot.bodies.size()", slots,
          "must be <= the World's " + std::to_string(w.bodyCount) +
              " body slots (restore a snapshot into the World that reached its frame, or later)");
  requireRestorable(snapshot);
  // The snapshot's bodies own the first particles; their contact history must come with them.
  const std::uint32_t particles = slots == 0 ? 0u : w.particleEnd(slots - 1);
  const std::size_t expected = w.keepsHistory() ? particles : 0u;
  require(snapshot.contacts.size() == expected, "WorldSnapshot.contacts.size()",
          double(snapshot.contacts.size()),
          "must be " + std::to_string(expected) +
              (w.keepsHistory() ? " (the particles of its bodies, under ContactLaw::HertzMindlin)"
                                : " (ContactLaw::PaperViscous keeps no contact history)"));
  const std::size_t rolling = w.keepsRollingHistory() ? particles : 0u;
  require(snapshot.rolling.size() == rolling, "WorldSnapshot.rolling.size()",
          double(snapshot.rolling.size()),
          "must be " + std::to_string(rolling) +
              (w.keepsRollingHistory()
                   ? " (the particles of its bodies, with rolling friction)"
                   : " (a World without rolling friction keeps no rolling springs)"));
  // With sleep a sleeper's forces are not computed again: a touched one's balance sums them.
  const std::size_t forces = w.sleep.enabled ? particles : 0u;
  require(snapshot.forces.size() == forces, "WorldSnapshot.forces.size()",
          double(snapshot.forces.size()),
          "must be " + std::to_string(forces) +
              (w.sleep.enabled ? " (the particles of its bodies, with sleep)"
                               : " (a World without sleep computes every force afresh)"));
  w.gpu->makeCurrent();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  // Only the snapshot's fields change: each vec4's w (mass, inverse mass and the like) and the
  // other flags stay as the World has them.
  const std::size_t count = w.bodyCount;
  std::vector<GpuVec4> position(count), orientation(count), velocity(count), spin(count);
  std::vector<GpuUVec4> info(count);
  w.buffers[kBodyPosition].download(0, count * sizeof(GpuVec4), position.data());
  w.buffers[kBodyOrientation].download(0, count * sizeof(GpuVec4), orientation.data());
  w.buffers[kBodyVelocity].download(0, count * sizeof(GpuVec4), velocity.data());
  w.buffers[kBodyAngularVelocity].download(0, count * sizeof(GpuVec4), spin.data());
  w.buffers[kBodyInfo].download(0, count * sizeof(GpuUVec4), info.data());
  for (std::size_t i = 0; i < count; ++i) {
    if (i >= slots) {
      info[i].z &= ~kBodyAlive;
      continue;
    }
    const StoredBody& b = snapshot.bodies[i];
    position[i] = {b.position[0], b.position[1], b.position[2], position[i].w};
    const Quat& q = b.principalOrientation;
    orientation[i] = {q.x, q.y, q.z, q.w};
    velocity[i] = {b.velocity[0], b.velocity[1], b.velocity[2], std::bit_cast<float>(b.calm)};
    spin[i] = {b.angularVelocity[0], b.angularVelocity[1], b.angularVelocity[2], spin[i].w};
    info[i].z = b.alive ? (info[i].z | kBodyAlive) : (info[i].z & ~kBodyAlive);
  }
  w.buffers[kBodyPosition].upload(0, count * sizeof(GpuVec4), position.data());
  w.buffers[kBodyOrientation].upload(0, count * sizeof(GpuVec4), orientation.data());
  w.buffers[kBodyVelocity].upload(0, count * sizeof(GpuVec4), velocity.data());
  w.buffers[kBodyAngularVelocity].upload(0, count * sizeof(GpuVec4), spin.data());
  w.buffers[kBodyInfo].upload(0, count * sizeof(GpuUVec4), info.data());
  if (w.keepsHistory()) uploadContacts(w.buffers, snapshot.contacts, w.particleCount);
  if (w.keepsRollingHistory()) uploadRolling(w.buffers, snapshot.rolling, w.particleCount);
  uploadForces(w.buffers, snapshot.forces);
  // The snapshot's slots hold the bodies of its ids; a slot added after it, its own.
  std::vector<std::uint32_t> ids;
  if (!snapshot.bodyIds.empty()) {
    ids = snapshot.bodyIds;
    for (std::uint32_t slot = slots; slot < w.bodyCount; ++slot) ids.push_back(slot);
  }
  w.setIds(ids);
  gl::check("World::restoreSnapshot");
  w.steps = snapshot.steps;
  w.simTime = snapshot.simulatedTime;
  w.gridValid = false;
  w.markParticlesDirty(0, w.particleCount);
  w.markBodiesChanged(0, w.bodyCount);
  w.listsStale = true;
  w.accumulator = snapshot.unsteppedTime;
  w.heldSubsteps = snapshot.heldSubsteps;
}

}  // namespace sandphys
