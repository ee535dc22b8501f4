#include "scenes/kit/readback.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sandphys::scenes::kit {

Reference::Reference(std::vector<BodyState> bodies) : m_bodies(std::move(bodies)) {
  for (std::size_t i = 0; i < m_bodies.size(); ++i) {
    const BodyState& body = m_bodies[i];
    if (!body.granule) continue;
    if (body.id.index >= m_bySlot.size()) m_bySlot.resize(body.id.index + 1, kNone);
    m_bySlot[body.id.index] = static_cast<std::uint32_t>(i);
  }
}

const BodyState* Reference::before(const BodyState& now) const {
  if (now.id.index >= m_bySlot.size() || m_bySlot[now.id.index] == kNone) return nullptr;
  return &m_bodies[m_bySlot[now.id.index]];
}

const BodyState* findBody(std::span<const BodyState> bodies, BodyId id) {
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

double meanDisplacement(const Reference& reference, std::span<const BodyState> bodies,
                        const Vec3& direction) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : granulesIn(bodies)) {
    const BodyState* before = reference.before(body);
    if (!before) continue;
    sum += dot(body.position - before->position, direction);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

float percentile(std::vector<float>& values, double fraction) {
  const auto rank = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                   values.end());
  return values[rank];
}

float pileSurface(std::span<const BodyState> bodies, const std::function<bool(const Vec3&)>& inside,
                  float outerRadius) {
  std::vector<float> heights;
  heights.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && inside(body.position)) heights.push_back(body.position.y);
  }
  if (heights.empty()) return 0.0f;
  return percentile(heights, 0.99) + outerRadius;
}

}  // namespace sandphys::scenes::kit
