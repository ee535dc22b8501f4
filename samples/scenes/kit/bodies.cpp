#include "scenes/kit/bodies.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scenes/kit/geometry.h"

namespace sandphys::scenes::kit {

GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed) {
  return {.center = {0.0f, lift + 0.5f * blockSpan(counts[1], spacing), 0.0f},
          .countX = counts[0],
          .countY = counts[1],
          .countZ = counts[2],
          .spacing = spacing,
          .seed = seed};
}

const BodyState* find(std::span<const BodyState> bodies, BodyId id) {
  const auto body = std::ranges::find_if(
      bodies, [&](const BodyState& b) { return id.isValid() && b.id.index == id.index; });
  return body == bodies.end() ? nullptr : &*body;
}

std::optional<BodyForce> takeForceOn(World& world, BodyId id) {
  for (const BodyForce& force : world.takeBodyForces()) {
    if (force.body == id) return force;
  }
  return std::nullopt;
}

SceneBody sceneBody(std::string name, const BodyState& state, Vec3 up) {
  const float upright = std::clamp(rotate(state.orientation, up).y, -1.0f, 1.0f);
  return {.name = std::move(name),
          .position = state.position,
          .orientation = state.orientation,
          .speed = length(state.velocity),
          .tiltDegrees = std::acos(upright) * 180.0f / std::numbers::pi_v<float>};
}

}  // namespace sandphys::scenes::kit
