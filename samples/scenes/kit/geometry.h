#pragma once

#include <cstdint>
#include <ranges>
#include <span>
#include <string_view>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// kGranuleReach in float, as scenes compute their geometry: the largest distance from a
/// granule's centre to the surface of one of its particles, d.
inline constexpr float kReach = static_cast<float>(kGranuleReach);
/// Largest jitter of a block granule per axis, d (GranuleBlock's default jitter at the default
/// spacing).
inline const float kJitter = GranuleBlock{}.jitter * kDefaultGranuleSpacing;

/// Granules in a block of `counts`, in 64 bits so that a product of three counts cannot wrap.
inline std::uint64_t granuleCount(const Count3& counts) {
  return static_cast<std::uint64_t>(counts[0]) * counts[1] * counts[2];
}

/// Height between the lowest and the highest layer's centres of a block with `layers` layers at
/// `spacing` (m), m.
inline float blockSpan(std::uint32_t layers, float spacing) {
  return static_cast<float>(layers - 1) * spacing;
}

/// Sets `settings`' capacities to exactly `granules` granules plus `bodies` other bodies of
/// `particles` particles in all. Throws InvalidArgument naming `scene` and the counts when that
/// is more than a World can index.
void reserveExactly(WorldSettings& settings, std::string_view scene, std::uint64_t granules,
                    std::uint64_t bodies = 0, std::uint64_t particles = 0);

/// The granules of a read-back that are alive.
inline auto granulesIn(std::span<const BodyState> bodies) {
  return bodies | std::views::filter([](const BodyState& b) { return b.alive && b.granule; });
}

/// Mass of one granule of the World made from `settings`, kg.
float granuleMass(const WorldSettings& settings);

/// Angle between a body's up axis at the start (the template's y) and now, degrees, for an
/// orientation `q` (w, x, y, z): the world y component of the rotated y axis is 1 - 2 (x² + z²).
float tiltDegrees(const Quat& q);

/// A read-back kept as the reference of later measurements (the berm before the push, the block
/// at release), looked up by body slot.
class Reference {
 public:
  Reference() = default;
  // Implicit: any read-back can serve as a reference.
  Reference(std::vector<BodyState> bodies);  // NOLINT(google-explicit-constructor)

  /// The granule `now` was in the reference, or nullptr when it was not there.
  const BodyState* before(const BodyState& now) const;
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::span<const BodyState> bodies() const { return m_bodies; }

 private:
  std::vector<BodyState> m_bodies;
  std::vector<std::uint32_t> m_bySlot;  // slot -> position in m_bodies, kNone if absent
};

}  // namespace sandphys::scenes::kit
