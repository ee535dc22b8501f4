#include "scenes/sand_box_pour.h"

#include <algorithm>
#include <cmath>

#include "scenes/kit/checks.h"
#include "scenes/kit/course.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/pour.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kReach;
// Granules slower than this (m/s) belong to the pile: the falling ones leave the emitter at
// kit::kMinPourSpeed or more and only speed up.
constexpr float kRestSpeed = 0.3f;

using C = SandBoxPourConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"rate", &C::rate, "granules/s", 1.0, 1e5, "pour rate"},
    {"granules", &C::granules, "", 1, 1e8, "granules poured in total (the emitter's budget)"},
    {"box-width", &C::boxWidth, "d", 4.0, 1e4, "inner width of the box along x and z"},
    {"box-height", &C::boxHeight, "d", 4.0, 1e4, "inner height of the box"},
    {"emitter-height", &C::pourHeight, "d", 2.0, 1e4, "height of the emitter above the floor"},
    {"emitter-size", &C::outlet, "d", 0.5, 1e4, "width of the square emitter"},
    {"block", &C::block, "", 0, 1024,
     "bed of granules on the floor before the pour, x, y (layers), z; 0,0,0 for none"},
});

}  // namespace

std::span<const kit::Param<C>> SandBoxPour::table() const {
  return kTable;
}

WorldSettings SandBoxPour::worldSettings() const {
  const Config& c = m_config;
  const auto check = [&](std::string_view what, float needs, std::string_view limit, float room) {
    kit::require(needs <= room, name(), what, " needs ", needs, " d, more than ", limit, " ", room,
                 " d");
  };
  check("emitter-size with a granule's reach each side", c.outlet + 2.0f * kReach, "box-width",
        c.boxWidth);
  check("emitter-height with a granule's reach", c.pourHeight + kReach, "box-height", c.boxHeight);
  if (bedGranules() > 0) {
    const auto span = [&](int i) { return kit::blockSpan(c.block[i], kDefaultGranuleSpacing); };
    // Lattice, jitter and reach on both sides.
    const auto wide = [&](int i) { return span(i) + 2.0f * kit::kJitter + 2.0f * kReach; };
    check("the bed (block) along x or z", std::max(wide(0), wide(2)), "box-width", c.boxWidth);
    // A granule's room above the bed's top.
    check("the bed (block) in height", kit::kLatticeGap + span(1) + kReach + kReach,
          "emitter-height", c.pourHeight);
  }
  pour().checkSpeed(name(), "emitter-size");
  return kit::worldSettings(name(), d(),
                            {.granules = std::uint64_t(c.granules) + bedGranules(),
                             .maxSpeed = pour().guardSpeed(),
                             .stepsPerContact = kit::kGuardStepsPerContact,
                             .youngsModulus = c.youngsModulus});
}

void SandBoxPour::build(World& world) {
  world.addCollider(kit::containerBox(bounds()));
  const bool bed = bedGranules() > 0;
  const float spacing = kDefaultGranuleSpacing * d();
  const float bedHeight = bed ? kit::blockSpan(m_config.block[1], spacing) : 0.0f;
  if (bed) {
    // The seed is not the emitter's.
    world.addGranules(kit::blockAbove(kit::kLatticeGap * d(), m_config.block, spacing,
                                      m_config.seed * 1000003u + 1u));
  }
  // Calm means nothing while the bed collapses onto the floor (its top layer falls about its own
  // height) or the last granule falls from the emitter. The bed's wait is limited from its drop,
  // the pile's from the pour's end.
  const double g = length(world.settings().gravity);
  const double bedLanding =
      bed ? 1.5 * kit::fallTime(bedHeight + kit::kLatticeGap * d(), 0.0, g) : 0.0;
  m_course = kit::PourCourse({.settleSpeed = m_config.settleSpeed,
                              .maxSettleSeconds = m_config.maxSettleSeconds - bedLanding,
                              .actAfter = bedLanding,
                              .minRestSeconds = pour().landingSeconds(g),
                              .maxRestSeconds = m_config.maxSettleSeconds,
                              .actFirst = !bed},
                             kit::granuleMass(world.settings()), m_config.granules, bedGranules());
  if (!bed) world.addEmitter(pour().emitter(0.0f, m_config.seed));
}

void SandBoxPour::update(World& world, const StepReport& report, double simTime) {
  m_course.count(world, simTime);
  // While the bed settles its granules are all there are; once poured, the pour's join them.
  if (m_course.update(report, simTime, world.granulesSpawned()) && m_course.acting()) {
    world.addEmitter(pour().emitter(0.0f, m_config.seed));
  }
}

std::array<float, 2> SandBoxPour::pileExtent(std::span<const BodyState> bodies) const {
  std::vector<float> heights;
  std::vector<float> radii;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    const Vec3& p = body.position;
    if (dot(body.velocity, body.velocity) < kRestSpeed * kRestSpeed && contains(p)) {
      heights.push_back(p.y);
      radii.push_back(std::hypot(p.x, p.z));
    }
  }
  if (heights.empty()) return {0.0f, 0.0f};
  return {kit::percentile(heights, 0.99) + kReach * d(),
          kit::percentile(radii, 0.99) + kReach * d()};
}

std::vector<SceneMetric> SandBoxPour::metrics(std::span<const BodyState> bodies) const {
  const auto [height, radius] = pileExtent(bodies);
  const double pourEnd = m_course.actEnd();
  return {
      {"granules_poured", static_cast<double>(m_course.poured())},
      {"granules_budget", static_cast<double>(m_config.granules)},
      {"bed_granules", static_cast<double>(bedGranules())},
      {"pour_rate_per_s", m_config.rate},
      {"pour_seconds", pourEnd >= 0.0 ? pourEnd - m_course.actStart() : 0.0},
      {"emitter_speed_m_per_s", pour().speed()},
      {"pile_height_m", height},
      {"pile_height_d", static_cast<double>(height) / d()},
      {"footprint_radius_m", radius},
      {"footprint_radius_d", static_cast<double>(radius) / d()},
      {"box_half_width_m", halfWidth()},
  };
}

SceneBounds SandBoxPour::bounds() const {
  const float half = halfWidth();
  return {{-half, 0.0f, -half}, {half, m_config.boxHeight * d(), half}};
}

}  // namespace sandphys::scenes
