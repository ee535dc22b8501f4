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

/// The rolling springs of the first `particles` particles (rollingSlots; rolling friction).
/// Sync point.
std::vector<StoredRolling> downloadRolling(const WorldBuffers& buffers, std::uint32_t particles);

/// Puts `rolling` back into the first rolling.size() particles and zeroes the springs of the
/// particles after them, up to `particles`.
void uploadRolling(WorldBuffers& buffers, const std::vector<StoredRolling>& rolling,
                   std::uint32_t particles);

/// The last computed force and torque of the first `particles` particles (particleForce,
/// particleTorque; sleep comes with ContactLaw::HertzMindlin only). Sync point.
std::vector<StoredForces> downloadForces(const WorldBuffers& buffers, std::uint32_t particles);

/// Puts `forces` back into the first forces.size() particles.
void uploadForces(WorldBuffers& buffers, const std::vector<StoredForces>& forces);

}  // namespace sandphys::detail
