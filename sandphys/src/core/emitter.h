#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/granule_spawner.h"
#include "sandphys/spawn.h"

namespace sandphys::detail {

/// CPU side of an emitter: decides which granules to add in each substep. Granules are placed on
/// a lattice of the emitting rectangle, one layer at a time in a shuffled order; a new layer
/// starts only once the previous one has had time to move one spacing away, so that new granules
/// never overlap the ones emitted before (the effective rate is capped by that).
class EmitterState {
 public:
  EmitterState(const EmitterSettings& settings, float particleDiameter);

  /// Granules due after `dt` more seconds, at most `room`. Sets `blocked` when capacity, not the
  /// rate, stopped it. CPU work is proportional to the granules returned.
  std::vector<GranuleSpawn> advance(double dt, std::uint32_t room, bool& blocked);
  bool finished() const { return m_emitted >= m_settings.maxGranules; }
  std::uint32_t emitted() const { return m_emitted; }

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
