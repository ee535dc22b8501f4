#include "scenes/repose_heap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "scenes/heap_metrics.h"
#include "scenes/kit/checks.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/pour.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

// Bulk volume of one granule in a settled heap, d³ (its four spheres fill 2.1 d³, loosely packed).
constexpr double kSettledVolume = 3.6;
// Room left between the foot of the heap and the floor's edge, d.
constexpr float kFootMargin = 4.0f;

using C = ReposeHeapConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"granules", &C::granules, "", 1, 1e8, "granules poured"},
    {"outlet", &C::outlet, "d", 0.5, 1e4, "width of the emitter's square"},
    {"rate", &C::rate, "granules/s", 1.0, 1e5, "pour rate"},
    {"pour-height", &C::pourHeight, "d", 1.0, 1e4, "height of the emitter above the floor"},
    {"floor-radius", &C::floorRadius, "d", 2.0, 1e4, "radius of the rough floor"},
});

}  // namespace

std::span<const kit::Param<C>> ReposeHeap::table() const {
  return kTable;
}

float ReposeHeap::floorRadiusHolding(std::uint32_t granules, float angleDegrees) {
  kit::require(angleDegrees > 0.0f && angleDegrees < 90.0f, "repose-heap", "the flank's angle ",
               angleDegrees, "° must lie in (0°, 90°)");
  // A cone of radius r and flank angle θ holds π r³ tan θ / 3.
  const double slope = std::tan(angleDegrees * std::numbers::pi / 180.0);
  const double radius = std::cbrt(3.0 * kSettledVolume * granules / (std::numbers::pi * slope));
  return static_cast<float>(radius) + kFootMargin;
}

WorldSettings ReposeHeap::worldSettings() const {
  const Config& c = m_config;
  kit::require(0.5f * c.outlet + kit::kReach <= c.floorRadius, name(), "outlet ", c.outlet,
               " d is wider than the floor (floor-radius ", c.floorRadius, " d)");
  pour().checkAboveFloor(name());
  return kit::worldSettings(
      name(), d(),
      {.granules = c.granules,
       .bodies = 1,
       .particles = roughFloorParticles(RoughFloor{.radius = c.floorRadius * d()}, d()),
       .maxSpeed = pour().guardSpeed(),
       .stepsPerContact = c.stepsPerContact,
       .youngsModulus = c.youngsModulus,
       .friction = c.friction,
       .restitution = c.restitution});
}

void ReposeHeap::build(World& world) {
  m_course = kit::PourCourse(pour().course(m_config.settleSpeed, m_config.maxSettleSeconds,
                                           length(world.settings().gravity)),
                             kit::granuleMass(world.settings()), m_config.granules);
  const float radius = m_config.floorRadius * d();
  world.addRoughFloor(RoughFloor{.radius = radius, .spacing = d()});
  world.addSink(pour().sink(radius));
  world.addEmitter(pour().emitter(0.0f, m_config.seed));
}

bool ReposeHeap::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::hypot(centre.x, centre.z) <= m_config.floorRadius * d();
}

analysis::HeapAngle ReposeHeap::heapAngle(std::span<const BodyState> bodies) const {
  std::vector<Vec3> centres;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    if (contains(body.position)) centres.push_back(body.position);
  }
  // The floor's surface is the top of its particles; cells one granule wide.
  return analysis::angleOfRepose(centres, {.floorY = 0.5 * d(),
                                           .binWidth = 2.0 * kGranuleReach * d(),
                                           .maxRadius = m_config.floorRadius * d()});
}

std::vector<SceneMetric> ReposeHeap::metrics(std::span<const BodyState> bodies) const {
  std::uint32_t onFloor = 0;
  std::uint32_t elsewhere = 0;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    (contains(body.position) ? onFloor : elsewhere) += 1;
  }
  const std::uint32_t poured = m_course.poured();
  std::vector<SceneMetric> result{
      {"granules_poured", static_cast<double>(poured)},
      {"granules_on_floor", static_cast<double>(onFloor)},
      {"granules_off_floor", static_cast<double>(poured - std::min(poured, onFloor))},
      {"granules_in_flight", static_cast<double>(elsewhere)},
      {"pour_end_s", m_course.actEnd()},
      {"friction", m_config.friction},
      {"settled", m_course.calm() ? 1.0 : 0.0},
  };
  appendHeapAngleMetrics(
      result, [&] { return heapAngle(bodies); }, d());
  return result;
}

SceneBounds ReposeHeap::bounds() const {
  const float r = m_config.floorRadius * d();
  return pour().bounds(r, r);
}

}  // namespace sandphys::scenes
