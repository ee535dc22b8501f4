#include "scenes/kit/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace sandphys::scenes::kit {

void reserveExactly(WorldSettings& settings, std::string_view scene, std::uint64_t granules,
                    std::uint64_t bodies, std::uint64_t particles) {
  constexpr std::uint64_t kLimit = std::numeric_limits<std::uint32_t>::max();
  const std::uint64_t allParticles = 4 * granules + particles;
  if (granules > kLimit || allParticles > kLimit) {
    throw InvalidArgument(std::string(scene) + ": " + std::to_string(granules) + " granules and " +
                          std::to_string(particles) +
                          " particles of other bodies are more than a World can index (" +
                          std::to_string(kLimit) + " particles)");
  }
  settings.maxBodies = static_cast<std::uint32_t>(granules + bodies);
  settings.maxParticles = static_cast<std::uint32_t>(allParticles);
}

float granuleMass(const WorldSettings& settings) {
  return tetrahedronTemplate(settings.particleDiameter, settings.material.density).mass;
}

float tiltDegrees(const Quat& q) {
  const float up = std::clamp(1.0f - 2.0f * (q.x * q.x + q.z * q.z), -1.0f, 1.0f);
  return std::acos(up) * 180.0f / std::numbers::pi_v<float>;
}

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

}  // namespace sandphys::scenes::kit
