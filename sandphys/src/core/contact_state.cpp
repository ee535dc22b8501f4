// The particle state of snapshots between the GPU's layout and the snapshot's: the contact history
// (gpu_buffers.def: slot k of particle i is entry 4 i + k % 4 of group buffer k / 4) and
// StoredContacts, the rolling springs (entry 12 i + k of rollingSlots) and StoredRolling, and with
// sleep the last computed forces and StoredForces.
#include "core/contact_state.h"

#include <array>
#include <string>

#include "core/assert.h"

namespace sandphys::detail {

using SlotWords = std::array<std::uint32_t, 4>;

std::vector<StoredContacts> downloadContacts(const WorldBuffers& buffers, std::uint32_t particles) {
  std::vector<StoredContacts> out(particles);
  if (particles == 0) return out;
  std::vector<SlotWords> group(std::size_t(particles) * kContactSlotsPerGroup);
  for (std::uint32_t g = 0; g < kContactSlotGroups; ++g) {
    buffers[Binding(kContactSlots0 + g)].download(0, group.size() * sizeof(SlotWords),
                                                  group.data());
    for (std::uint32_t i = 0; i < particles; ++i) {
      for (std::uint32_t k = 0; k < kContactSlotsPerGroup; ++k) {
        out[i].slots[g * kContactSlotsPerGroup + k] =
            group[std::size_t(i) * kContactSlotsPerGroup + k];
      }
    }
  }
  std::vector<SlotWords> pairs(particles);
  buffers[kContactPairs].download(0, pairs.size() * sizeof(SlotWords), pairs.data());
  for (std::uint32_t i = 0; i < particles; ++i) {
    for (std::uint32_t w = 0; w < out[i].pairs.size(); ++w) out[i].pairs[w] = pairs[i][w];
  }
  return out;
}

void uploadContacts(WorldBuffers& buffers, const std::vector<StoredContacts>& contacts,
                    std::uint32_t particles) {
  SANDPHYS_ASSERT(contacts.size() <= particles,
                  std::to_string(contacts.size()) + " particles' contact history for " +
                      std::to_string(particles) + " particles in use");
  if (particles == 0) return;
  std::vector<SlotWords> group(std::size_t(particles) * kContactSlotsPerGroup, SlotWords{});
  for (std::uint32_t g = 0; g < kContactSlotGroups; ++g) {
    for (std::uint32_t i = 0; i < contacts.size(); ++i) {
      for (std::uint32_t k = 0; k < kContactSlotsPerGroup; ++k) {
        group[std::size_t(i) * kContactSlotsPerGroup + k] =
            contacts[i].slots[g * kContactSlotsPerGroup + k];
      }
    }
    buffers[Binding(kContactSlots0 + g)].upload(0, group.size() * sizeof(SlotWords), group.data());
  }
  std::vector<SlotWords> pairs(particles, SlotWords{});
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    for (std::uint32_t w = 0; w < contacts[i].pairs.size(); ++w) pairs[i][w] = contacts[i].pairs[w];
  }
  buffers[kContactPairs].upload(0, pairs.size() * sizeof(SlotWords), pairs.data());
  // The contacts each particle counted in the substep that left this history (pairs and
  // colliders, as contacts.comp writes them): a sleeper keeps them until it is computed again,
  // and WorldStats::contacts reads them. The totals beside them (guards) run on.
  std::vector<GpuUVec4> stats(particles);
  buffers[kParticleStats].download(0, stats.size() * sizeof(GpuUVec4), stats.data());
  for (std::uint32_t i = 0; i < particles; ++i) {
    stats[i].x = stats[i].w = 0;
    if (i >= contacts.size()) continue;
    for (const SlotWords& slot : contacts[i].slots) {
      const std::uint32_t key = slot[3];
      if (key == 0) continue;
      ++((key & kSlotCollider) ? stats[i].w : stats[i].x);
    }
  }
  buffers[kParticleStats].upload(0, stats.size() * sizeof(GpuUVec4), stats.data());
}

std::vector<StoredRolling> downloadRolling(const WorldBuffers& buffers, std::uint32_t particles) {
  std::vector<StoredRolling> out(particles);
  if (particles == 0) return out;
  std::vector<SlotWords> words(std::size_t(particles) * kContactSlots);
  buffers[kRollingSlots].download(0, words.size() * sizeof(SlotWords), words.data());
  for (std::uint32_t i = 0; i < particles; ++i) {
    for (std::uint32_t k = 0; k < kContactSlots; ++k) {
      const SlotWords& w = words[std::size_t(i) * kContactSlots + k];
      out[i].springs[k] = {w[0], w[1], w[2]};
    }
  }
  return out;
}

void uploadRolling(WorldBuffers& buffers, const std::vector<StoredRolling>& rolling,
                   std::uint32_t particles) {
  SANDPHYS_ASSERT(rolling.size() <= particles, std::to_string(rolling.size()) +
                                                   " particles' rolling springs for " +
                                                   std::to_string(particles) + " particles in use");
  if (particles == 0) return;
  std::vector<SlotWords> words(std::size_t(particles) * kContactSlots, SlotWords{});
  for (std::size_t i = 0; i < rolling.size(); ++i) {
    for (std::uint32_t k = 0; k < kContactSlots; ++k) {
      const auto& spring = rolling[i].springs[k];
      words[i * kContactSlots + k] = {spring[0], spring[1], spring[2], 0u};
    }
  }
  buffers[kRollingSlots].upload(0, words.size() * sizeof(SlotWords), words.data());
}

std::vector<StoredForces> downloadForces(const WorldBuffers& buffers, std::uint32_t particles) {
  std::vector<StoredForces> out(particles);
  if (particles == 0) return out;
  std::vector<SlotWords> words(particles);
  buffers[kParticleForce].download(0, words.size() * sizeof(SlotWords), words.data());
  for (std::uint32_t i = 0; i < particles; ++i) out[i].force = words[i];
  buffers[kParticleTorque].download(0, words.size() * sizeof(SlotWords), words.data());
  for (std::uint32_t i = 0; i < particles; ++i) out[i].torque = words[i];
  return out;
}

void uploadForces(WorldBuffers& buffers, const std::vector<StoredForces>& forces) {
  if (forces.empty()) return;
  std::vector<SlotWords> words(forces.size());
  for (std::size_t i = 0; i < forces.size(); ++i) words[i] = forces[i].force;
  buffers[kParticleForce].upload(0, words.size() * sizeof(SlotWords), words.data());
  for (std::size_t i = 0; i < forces.size(); ++i) words[i] = forces[i].torque;
  buffers[kParticleTorque].upload(0, words.size() * sizeof(SlotWords), words.data());
}

}  // namespace sandphys::detail
