#include "core/emitter.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/validation.h"
#include "core/world_checks.h"

namespace sandphys {

namespace {

// Columns (along x) and rows (along z) of an emitter's lattice, in double so that a rectangle
// of any size is counted without overflow.
std::array<double, 2> emitterLattice(const EmitterSettings& s, float particleDiameter) {
  const double spacing = kDefaultGranuleSpacing * particleDiameter;
  return {1.0 + std::floor(2.0 * s.halfExtentX / spacing),
          1.0 + std::floor(2.0 * s.halfExtentZ / spacing)};
}

}  // namespace

std::uint64_t emitterLayerSlots(const EmitterSettings& emitter, float particleDiameter) {
  const auto [columns, rows] = emitterLattice(emitter, particleDiameter);
  constexpr double kMax = 9.0e18;  // below 2^63: the cast stays defined for any rectangle
  return std::uint64_t(std::min(columns * rows, kMax));
}

namespace detail {

EmitterState::EmitterState(const EmitterSettings& s, float particleDiameter, std::uint32_t maxSlots)
    : m_settings(s), m_rng(s.seed) {
  requireFinite("EmitterSettings.center.x", s.center.x);
  requireFinite("EmitterSettings.center.y", s.center.y);
  requireFinite("EmitterSettings.center.z", s.center.z);
  requirePositive("EmitterSettings.halfExtentX", s.halfExtentX, "(m)");
  requirePositive("EmitterSettings.halfExtentZ", s.halfExtentZ, "(m)");
  requirePositive("EmitterSettings.rate", s.rate, "(granules/s)");
  const double speed =
      std::sqrt(double(s.velocity.x) * s.velocity.x + double(s.velocity.y) * s.velocity.y +
                double(s.velocity.z) * s.velocity.z);
  requirePositive("EmitterSettings.velocity (speed)", speed,
                  "(m/s): emitted granules must move away");

  const double spacing = kDefaultGranuleSpacing * particleDiameter;
  const auto [columns, rows] = emitterLattice(s, particleDiameter);
  require(columns * rows <= double(maxSlots), "EmitterSettings.halfExtentX/Z (lattice slots)",
          columns * rows,
          "must be <= WorldSettings.maxBodies = " + std::to_string(maxSlots) +
              ": a layer of the rectangle's lattice (spacing " + formatValue(spacing) +
              " m) must fit in the World");
  requireResolvable("EmitterSettings.center", s.center,
                    std::hypot(double(s.halfExtentX), double(s.halfExtentZ)), particleDiameter);
  const int nx = int(columns);
  const int nz = int(rows);
  m_slots.reserve(std::size_t(columns * rows));
  for (int z = 0; z < nz; ++z) {
    for (int x = 0; x < nx; ++x) {
      m_slots.push_back({float(s.center.x + (x - 0.5 * (nx - 1)) * spacing), s.center.y,
                         float(s.center.z + (z - 0.5 * (nz - 1)) * spacing)});
    }
  }
  m_order.resize(m_slots.size());
  m_layerInterval = spacing / speed;
  m_layerAge = m_layerInterval;
  m_nextSlot = m_slots.size();
  require(s.rate <= maxRate(), "EmitterSettings.rate", s.rate,
          "must be <= " + formatValue(std::floor(maxRate())) +
              " granules/s for this rectangle and speed (" + std::to_string(m_slots.size()) +
              " lattice slots every " + formatValue(m_layerInterval) +
              " s); enlarge the rectangle or the speed");
}

void EmitterState::shuffleLayer() {
  for (std::uint32_t i = 0; i < m_order.size(); ++i) m_order[i] = i;
  for (std::size_t i = m_order.size(); i > 1; --i) {
    std::size_t j = std::size_t(m_rng() % i);
    std::swap(m_order[i - 1], m_order[j]);
  }
}

std::vector<GranuleSpawn> EmitterState::advance(double dt, std::uint32_t room, bool& blocked) {
  std::vector<GranuleSpawn> out;
  if (finished()) return out;
  m_due = std::min(m_due + m_settings.rate * dt, double(m_slots.size()));
  m_layerAge += dt;
  const Vec3& v = m_settings.velocity;
  while (m_due >= 1.0 && !finished()) {
    if (m_nextSlot == m_slots.size()) {
      if (m_layerAge < m_layerInterval) break;
      shuffleLayer();
      m_nextSlot = 0;
      m_layerAge = 0.0;
    }
    if (room == 0) {
      blocked = true;
      break;
    }
    GranuleSpawn spawn;
    // Where this slot of the layer would be had it been emitted when the layer started.
    const Vec3& slot = m_slots[m_order[m_nextSlot++]];
    spawn.position = {float(slot.x + v.x * m_layerAge), float(slot.y + v.y * m_layerAge),
                      float(slot.z + v.z * m_layerAge)};
    spawn.orientation = randomOrientation(m_rng);
    spawn.velocity = m_settings.velocity;
    out.push_back(spawn);
    m_due -= 1.0;
    ++m_emitted;
    --room;
  }
  return out;
}

}  // namespace detail

}  // namespace sandphys
