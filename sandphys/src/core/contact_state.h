#pragma once

#include <cstdint>
#include <vector>

#include "core/world_impl.h"
#include "sandphys/snapshot.h"

namespace sandphys::detail {

/// The contact history of the first `particles` particles as the GPU stores it (slots in their
/// group buffers, pair counts). Sync point.
std::vector<StoredContacts> downloadContacts(const WorldBuffers& buffers, std::uint32_t particles);

/// Puts `contacts` back into the first contacts.size() particles and frees the slots of the
/// particles after them, up to `particles`; the contacts each particle counts (particleStats) are
/// those its slots hold. Sync point.
void uploadContacts(WorldBuffers& buffers, const std::vector<StoredContacts>& contacts,
                    std::uint32_t particles);

/// The last computed force and torque of the first `particles` particles (particleForce, and
/// particleTorque when `torques`: under HertzMindlin; else 0). Sync point.
std::vector<StoredForces> downloadForces(const WorldBuffers& buffers, std::uint32_t particles,
                                         bool torques);

/// Puts `forces` back into the first forces.size() particles (the torques when `torques`).
void uploadForces(WorldBuffers& buffers, const std::vector<StoredForces>& forces, bool torques);

}  // namespace sandphys::detail
