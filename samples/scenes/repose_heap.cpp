#include "scenes/repose_heap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "scenes/heap_metrics.h"
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

}  // namespace

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
  const std::uint64_t floorParticles =
      roughFloorParticles(RoughFloor{.radius = m_config.floorRadius * d()}, d());
  const std::uint64_t particles = 4ull * m_config.granules + floorParticles;
  if (m_config.granules == 0 || particles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(scene + "granules = " + std::to_string(m_config.granules) +
                          " must be >= 1 and, with the floor's " + std::to_string(floorParticles) +
                          " particles, fit a World's 2^32 particles");
  }
  if (0.5f * m_config.outlet + static_cast<float>(kGranuleReach) > m_config.floorRadius) {
    throw InvalidArgument(scene + "outlet " + numberText(m_config.outlet) +
                          " d is wider than the floor (floor-radius " +
                          numberText(m_config.floorRadius) + " d)");
  }
  if (m_config.pourHeight < 2.0f * static_cast<float>(kGranuleReach)) {
    throw InvalidArgument(scene + "pour-height " + numberText(m_config.pourHeight) +
                          " d leaves no room for a granule above the floor (at least " +
                          numberText(2.0f * static_cast<float>(kGranuleReach)) + " d)");
  }
  checkPourSpeed("repose-heap", "the outlet", 0.5f * m_config.outlet * d(), m_config.rate, d());
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.material.restitution = m_config.restitution;
  settings.maxBodies = m_config.granules + 1;  // + the floor
  settings.maxParticles = static_cast<std::uint32_t>(particles);
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
  m_settling = PourSettling(
      fallTime(m_config.pourHeight * d(), emitterSpeed(), gravityMagnitude(world.settings())),
      tetrahedronTemplate(d(), world.settings().material.density).mass, m_config.settleSpeed,
      m_config.maxSettleSeconds);
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
  m_settling.update(report, simTime, m_poured, m_config.granules);
}

std::string ReposeHeap::status() const {
  return m_settling.status(m_poured, m_config.granules);
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
      {"pour_end_s", m_settling.pourEnd()},
      {"friction", m_config.friction},
      {"settled", m_settling.calm() ? 1.0 : 0.0},
  };
  appendHeapAngleMetrics(
      result, [&] { return heapAngle(bodies); }, d());
  return result;
}

std::vector<SceneParameter> ReposeHeap::parameters() {
  return {
      {"granules", "granules poured", &m_config.granules, 1, 1e8},
      {"friction", "Coulomb friction coefficient of every contact", &m_config.friction, 0.0, 10.0},
      {"outlet", "width of the emitter's square, d", &m_config.outlet, 0.5, 1e4},
      {"rate", "pour rate, granules/s", &m_config.rate, 1.0, 1e5},
      {"pour-height", "height of the emitter above the floor, d", &m_config.pourHeight, 1.0, 1e4},
      {"floor-radius", "radius of the rough floor, d", &m_config.floorRadius, 2.0, 1e4},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"restitution", "coefficient of restitution", &m_config.restitution, 0.01, 1.0},
      {"settle-speed", "the heap has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the heap to settle after the pour, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"steps-per-contact", "substeps per Hertz contact time at the speed guard",
       &m_config.stepsPerContact, kMinStepsPerContact, 1e4},
      {"seed", "random seed of the emitter", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds ReposeHeap::bounds() const {
  const float r = m_config.floorRadius * d();
  return {{-r, -kSinkDepth * d(), -r}, {r, (m_config.pourHeight + 1.0f) * d(), r}};
}

}  // namespace sandphys::scenes
