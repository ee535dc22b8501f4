#include "scenes/box_drop.h"

#include <algorithm>
#include <array>

#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using C = BoxDropConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"block", &C::block, "", 1, 1024, "granules along x, y (layers), z"},
});

}  // namespace

std::span<const kit::Param<C>> BoxDrop::table() const {
  return kTable;
}

WorldSettings BoxDrop::worldSettings() const {
  const float blockHeight = static_cast<float>(m_config.block[1]) * kDefaultGranuleSpacing;
  const float drop = (m_config.dropHeight + blockHeight) * d();
  return kit::worldSettings(name(), d(),
                            {.granules = kit::granuleCount(m_config.block),
                             .maxSpeed = kit::pourGuardSpeed(0.0f, drop, kit::kGravity)});
}

void BoxDrop::build(World& world) {
  world.addCollider(kit::containerBox(bounds()));
  const float spacing = m_config.spacing * d();
  world.addGranules(
      kit::blockAbove(m_config.dropHeight * d(), m_config.block, spacing, m_config.seed));
}

std::vector<SceneMetric> BoxDrop::metrics(std::span<const BodyState> bodies) const {
  double sum = 0.0;
  double top = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    sum += body.position.y;
    top = std::max(top, static_cast<double>(body.position.y));
    ++count;
  }
  return {{"mean_height_m", count ? sum / static_cast<double>(count) : 0.0}, {"max_height_m", top}};
}

SceneBounds BoxDrop::bounds() const {
  const float halfWidth = m_config.boxHalfWidth * d();
  return {{-halfWidth, 0.0f, -halfWidth}, {halfWidth, m_config.boxHeight * d(), halfWidth}};
}

}  // namespace sandphys::scenes
