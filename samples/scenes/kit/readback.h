#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ranges>
#include <span>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// The granules of a read-back that are alive.
inline auto granulesIn(std::span<const BodyState> bodies) {
  return bodies | std::views::filter([](const BodyState& b) { return b.alive && b.granule; });
}

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

/// The body in `id`'s slot in a read-back, or nullptr when it is not there (or `id` is invalid).
const BodyState* findBody(std::span<const BodyState> bodies, BodyId id);

/// The sand's force on the body `id` since the last call (World::takeBodyForces, a sync point,
/// which restarts every body's sums), or nothing when the World reports none for it.
std::optional<BodyForce> takeForceOn(World& world, BodyId id);

/// `state` as the metrics report it, its tilt the angle between world y and `up` (the body's up
/// axis at the start, in its own frame) turned by its orientation now, degrees.
SceneBody sceneBody(std::string name, const BodyState& state, Vec3 up = {0.0f, 1.0f, 0.0f});

/// Mean displacement (m) along the unit vector `direction` of the alive granules of `bodies` from
/// where they were in `reference`; 0 when none was there.
double meanDisplacement(const Reference& reference, std::span<const BodyState> bodies,
                        const Vec3& direction);

/// The value below which `fraction` (in [0, 1]) of `values` lie; `values` must not be empty and
/// is reordered.
float percentile(std::vector<float>& values, double fraction);
/// Height (m) of the top surface of the granules in `bodies` that are alive and for whose centre
/// `inside` holds: the 99th percentile of their centre heights plus `outerRadius`, so that a few
/// bouncing granules do not count; 0 when there are none.
float pileSurface(std::span<const BodyState> bodies, const std::function<bool(const Vec3&)>& inside,
                  float outerRadius);

}  // namespace sandphys::scenes::kit
