#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/granule_spawner.h"
#include "sandphys/spawn.h"

namespace sandphys::detail {

/// CPU side of an emitter: decides which granules to add in each substep. Granules are placed on
/// a lattice of the emitting rectangle that moves with the emitter velocity, one layer at a time
/// in a shuffled order; a new layer starts when the previous one has moved one spacing on. So new
/// granules never start inside earlier ones, and the rate is bounded by the lattice: a rate above
/// maxRate() is refused at creation.
class EmitterState {
 public:
  /// Throws InvalidArgument naming the field for a rectangle whose layer holds more lattice
  /// slots than `maxSlots` (the World's body capacity: a layer that can never fit), checked
  /// before any slot is built.
  EmitterState(const EmitterSettings& settings, float particleDiameter, std::uint32_t maxSlots);

  /// Granules due after `dt` more seconds, at most `room`. Sets `blocked` when capacity, not the
  /// rate, stopped it. CPU work is proportional to the granules returned.
  std::vector<GranuleSpawn> advance(double dt, std::uint32_t room, bool& blocked);
  bool finished() const { return m_emitted >= m_settings.maxGranules; }
  /// Granules per second the lattice can take at this speed.
  double maxRate() const { return double(m_slots.size()) / m_layerInterval; }
  std::uint32_t emitted() const { return m_emitted; }
  const EmitterSettings& settings() const { return m_settings; }

 private:
  void shuffleLayer();

  EmitterSettings m_settings;
  std::vector<Vec3> m_slots;
  std::vector<std::uint32_t> m_order;
  std::size_t m_nextSlot = 0;
  double m_due = 0.0;
  double m_layerAge = 0.0;
  double m_layerInterval = 0.0;
  std::uint32_t m_emitted = 0;
  std::mt19937_64 m_rng;
};

}  // namespace sandphys::detail
