#include "scenes/box_drop.h"

#include "scenes/pour.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sandphys::scenes {

WorldSettings BoxDrop::worldSettings() const {
  WorldSettings settings;
  settings.particleDiameter = d();
  const std::uint64_t granules =
      static_cast<std::uint64_t>(m_config.block[0]) * m_config.block[1] * m_config.block[2];
  if (4 * granules > 0xffffffffu) {
    throw InvalidArgument("box-drop: block of " + std::to_string(granules) +
                          " granules is more than a World can index");
  }
  settings.maxBodies = static_cast<std::uint32_t>(granules);
  settings.maxParticles = static_cast<std::uint32_t>(4 * granules);
  const float blockHeight = static_cast<float>(m_config.block[1]) * kDefaultGranuleSpacing;
  settings.maxSpeed =
      pourGuardSpeed(0.0f, (m_config.dropHeight + blockHeight) * d(), gravityMagnitude(settings));
  settings.material.youngsModulus = sceneYoungsModulus(settings);
  return settings;
}

void BoxDrop::build(World& world) {
  const float halfWidth = m_config.boxHalfWidth * d();
  const float height = m_config.boxHeight * d();
  world.addCollider(Box{.center = {0.0f, 0.5f * height, 0.0f},
                        .halfExtents = {halfWidth, 0.5f * height, halfWidth},
                        .inside = true});
  const float spacing = m_config.spacing * d();
  const float blockHeight = static_cast<float>(m_config.block[1] - 1) * spacing;
  world.addGranules(
      GranuleBlock{.center = {0.0f, m_config.dropHeight * d() + 0.5f * blockHeight, 0.0f},
                   .countX = m_config.block[0],
                   .countY = m_config.block[1],
                   .countZ = m_config.block[2],
                   .spacing = spacing,
                   .seed = m_config.seed});
}

bool BoxDrop::contains(const Vec3& centre) const {
  const float halfWidth = m_config.boxHalfWidth * d();
  return centre.y >= 0.0f && centre.y <= m_config.boxHeight * d() &&
         std::abs(centre.x) <= halfWidth && std::abs(centre.z) <= halfWidth;
}

std::vector<SceneMetric> BoxDrop::metrics(std::span<const BodyState> bodies) const {
  double sum = 0.0;
  double top = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : bodies) {
    if (!body.alive || !body.granule) continue;
    sum += body.position.y;
    top = std::max(top, static_cast<double>(body.position.y));
    ++count;
  }
  return {{"mean_height_m", count ? sum / static_cast<double>(count) : 0.0}, {"max_height_m", top}};
}

std::vector<SceneParameter> BoxDrop::parameters() {
  return {
      {"block", "granules along x, y (layers), z", &m_config.block, 1, 1024},
      {"seed", "random seed of the block", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds BoxDrop::bounds() const {
  const float halfWidth = m_config.boxHalfWidth * d();
  return {{-halfWidth, 0.0f, -halfWidth}, {halfWidth, m_config.boxHeight * d(), halfWidth}};
}

}  // namespace sandphys::scenes
