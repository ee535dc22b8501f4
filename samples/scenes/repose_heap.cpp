#include "scenes/repose_heap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "scenes/heap_metrics.h"
#include "scenes/kit/geometry.h"
#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

// Depth of the sink's top below the floor's particle centres, d: past the floor's edge a grain
// that deep has left.
constexpr float kSinkDepth = 3.0f;
// Bulk volume of one granule in a settled heap, d³ (its four spheres fill 2.1 d³, loosely packed).
constexpr double kSettledVolume = 3.6;
// Room left between the foot of the heap and the floor's edge, d.
constexpr float kFootMargin = 4.0f;

using C = ReposeHeapConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"granules", &C::granules, "", 1, 1e8, "granules poured"},
    kit::frictionParam(&C::friction),
    {"outlet", &C::outlet, "d", 0.5, 1e4, "width of the emitter's square"},
    {"rate", &C::rate, "granules/s", 1.0, 1e5, "pour rate"},
    {"pour-height", &C::pourHeight, "d", 1.0, 1e4, "height of the emitter above the floor"},
    {"floor-radius", &C::floorRadius, "d", 2.0, 1e4, "radius of the rough floor"},
    kit::youngsModulusParam(&C::youngsModulus),
    kit::restitutionParam(&C::restitution),
    kit::settleSpeedParam(&C::settleSpeed),
    kit::maxSettleSecondsParam(&C::maxSettleSeconds),
    kit::stepsPerContactParam(&C::stepsPerContact),
    kit::seedParam(&C::seed),
    kit::diameterParam(&C::particleDiameter),
});

}  // namespace

std::span<const kit::Param<C>> ReposeHeap::table() const {
  return kTable;
}

float ReposeHeap::emitterSpeed() const {
  return pourSpeed(0.5f * m_config.outlet * d(), m_config.rate, d());
}

float ReposeHeap::floorRadiusHolding(std::uint32_t granules, float angleDegrees) {
  if (!(angleDegrees > 0.0f && angleDegrees < 90.0f)) {
    throw InvalidArgument("repose-heap: the flank's angle " + numberText(angleDegrees) +
                          "° must lie in (0°, 90°)");
  }
  // A cone of radius r and flank angle θ holds π r³ tan θ / 3.
  const double slope = std::tan(angleDegrees * std::numbers::pi / 180.0);
  const double radius = std::cbrt(3.0 * kSettledVolume * granules / (std::numbers::pi * slope));
  return static_cast<float>(radius) + kFootMargin;
}

WorldSettings ReposeHeap::worldSettings() const {
  const std::string scene = "repose-heap: ";
  if (0.5f * m_config.outlet + kit::kReach > m_config.floorRadius) {
    throw InvalidArgument(scene + "outlet " + numberText(m_config.outlet) +
                          " d is wider than the floor (floor-radius " +
                          numberText(m_config.floorRadius) + " d)");
  }
  if (m_config.pourHeight < 2.0f * kit::kReach) {
    throw InvalidArgument(scene + "pour-height " + numberText(m_config.pourHeight) +
                          " d leaves no room for a granule above the floor (at least " +
                          numberText(2.0f * kit::kReach) + " d)");
  }
  checkPourSpeed(name(), "the outlet", 0.5f * m_config.outlet * d(), m_config.rate, d());
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.material.restitution = m_config.restitution;
  kit::reserveExactly(settings, name(), m_config.granules, 1,
                      roughFloorParticles(RoughFloor{.radius = m_config.floorRadius * d()}, d()));
  // Settling is judged from every frame's kinetic energy.
  settings.statsEachFrame = true;
  settings.maxSpeed =
      pourGuardSpeed(emitterSpeed(), m_config.pourHeight * d(), gravityMagnitude(settings));
  settings.stepsPerContact = m_config.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

void ReposeHeap::build(World& world) {
  m_poured = 0;
  m_course = kit::Course(pourCourse(fallTime(m_config.pourHeight * d(), emitterSpeed(),
                                             gravityMagnitude(world.settings())),
                                    m_config.settleSpeed, m_config.maxSettleSeconds),
                         kit::granuleMass(world.settings()));
  const float radius = m_config.floorRadius * d();
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d()});
  // Everything that rolls off the floor's edge (or, by a fault, through it) ends here.
  const float wide = radius + m_config.pourHeight * d();
  world.addSink(Sink{.min = {-wide, -(kSinkDepth + 10.0f) * d(), -wide},
                     .max = {wide, -kSinkDepth * d(), wide}});
  const float half = 0.5f * m_config.outlet * d();
  world.addEmitter(EmitterSettings{.center = {0.0f, m_config.pourHeight * d(), 0.0f},
                                   .halfExtentX = half,
                                   .halfExtentZ = half,
                                   .rate = m_config.rate,
                                   .velocity = {0.0f, -emitterSpeed(), 0.0f},
                                   .maxGranules = m_config.granules,
                                   .seed = m_config.seed});
}

void ReposeHeap::update(World& world, const StepReport& report, double simTime) {
  m_poured = world.granulesSpawned();
  if (m_course.acting() && m_poured >= m_config.granules) m_course.endAct(simTime);
  m_course.update(report, simTime);
}

std::string ReposeHeap::status() const {
  return pourStatus(m_course, m_poured, m_config.granules);
}

bool ReposeHeap::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::hypot(centre.x, centre.z) <= m_config.floorRadius * d();
}

analysis::HeapAngle ReposeHeap::heapAngle(std::span<const BodyState> bodies) const {
  std::vector<Vec3> centres;
  centres.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && contains(body.position)) centres.push_back(body.position);
  }
  // The floor's surface is the top of its particles; cells one granule wide.
  return analysis::angleOfRepose(centres, {.floorY = 0.5 * d(),
                                           .binWidth = 2.0 * kGranuleReach * d(),
                                           .maxRadius = m_config.floorRadius * d()});
}

std::vector<SceneMetric> ReposeHeap::metrics(std::span<const BodyState> bodies) const {
  std::uint32_t onFloor = 0;
  std::uint32_t elsewhere = 0;
  for (const BodyState& body : bodies) {
    if (!body.granule || !body.alive) continue;
    (contains(body.position) ? onFloor : elsewhere) += 1;
  }
  std::vector<SceneMetric> result{
      {"granules_poured", static_cast<double>(m_poured)},
      {"granules_on_floor", static_cast<double>(onFloor)},
      {"granules_off_floor", static_cast<double>(m_poured - std::min(m_poured, onFloor))},
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
  return {{-r, -kSinkDepth * d(), -r}, {r, (m_config.pourHeight + 1.0f) * d(), r}};
}

}  // namespace sandphys::scenes
