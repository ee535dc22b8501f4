#include "scenes/sand_box_pour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>

#include "scenes/kit/geometry.h"
#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

using kit::kReach;
// Height of the bed's lowest centres above the floor, d: the reach and the jitter.
constexpr float kBedClearance = 1.4f;
// Substeps per Hertz contact time at the guard speed: the guard is the worst impact, slower
// contacts get more substeps, and 10 (the minimum is 8) halves the cost of the default 20.
constexpr float kStepsPerContact = 10.0f;
// Granules slower than this (m/s) belong to the pile: the falling ones leave the emitter at
// kMinPourSpeed or more and only speed up.
constexpr float kRestSpeed = 0.3f;

using C = SandBoxPourConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"rate", &C::rate, "granules/s", 1.0, 1e5, "pour rate"},
    {"granules", &C::granules, "", 1, 1e8, "granules poured in total (the emitter's budget)"},
    {"box-width", &C::boxWidth, "d", 4.0, 1e4, "inner width of the box along x and z"},
    {"box-height", &C::boxHeight, "d", 4.0, 1e4, "inner height of the box"},
    {"emitter-height", &C::emitterHeight, "d", 2.0, 1e4, "height of the emitter above the floor"},
    {"emitter-size", &C::emitterSize, "d", 0.5, 1e4, "width of the square emitter"},
    {"block", &C::block, "", 0, 1024,
     "bed of granules on the floor before the pour, x, y (layers), z; 0,0,0 for none"},
    {"settle-speed", &C::settleSpeed, "m/s", 0.0, 10.0,
     "the sand has settled below this rms speed"},
    {"max-settle-seconds", &C::maxSettleSeconds, "s", 0.0, 1e6,
     "longest wait for the bed or the pile to settle"},
    kit::youngsModulusParam(&C::youngsModulus),
    kit::seedParam(&C::seed),
    kit::diameterParam(&C::particleDiameter),
});

// The 99th percentile of `value` over the contained granules at rest in `bodies`, plus the
// granule's reach; 0 without such granules.
float pileExtent(const SandBoxPour& scene, std::span<const BodyState> bodies, float reach,
                 const std::function<float(const Vec3&)>& value) {
  std::vector<float> values;
  values.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    const Vec3& v = body.velocity;
    const bool atRest = v.x * v.x + v.y * v.y + v.z * v.z < kRestSpeed * kRestSpeed;
    if (body.alive && body.granule && atRest && scene.contains(body.position)) {
      values.push_back(value(body.position));
    }
  }
  return values.empty() ? 0.0f : percentile(values, 0.99) + reach;
}

}  // namespace

std::span<const kit::Param<C>> SandBoxPour::table() const {
  return kTable;
}

std::uint32_t SandBoxPour::bedGranules() const {
  return m_config.block[0] * m_config.block[1] * m_config.block[2];
}

std::uint32_t SandBoxPour::layerGranules() const {
  return emitterLayerGranules(emitterHalfExtent(), d());
}

float SandBoxPour::emitterSpeed() const {
  return pourSpeed(emitterHalfExtent(), m_config.rate, d());
}

WorldSettings SandBoxPour::worldSettings() const {
  const Config& c = m_config;
  const auto check = [&](const std::string& what, float needs, const char* limit, float room) {
    if (needs <= room) return;
    throw InvalidArgument("sand-box-pour: " + what + " needs " + numberText(needs) +
                          " d, more than " + limit + " " + numberText(room) + " d");
  };
  check("emitter-size with a granule's reach each side", c.emitterSize + 2.0f * kReach, "box-width",
        c.boxWidth);
  check("emitter-height with a granule's reach", c.emitterHeight + kReach, "box-height",
        c.boxHeight);
  if (bedGranules() > 0) {
    const auto span = [&](int axis) {
      return static_cast<float>(c.block[axis] - 1) * kDefaultGranuleSpacing;
    };
    // Lattice, jitter and reach on both sides.
    const auto wide = [&](int axis) { return span(axis) + 2.0f * kit::kJitter + 2.0f * kReach; };
    check("the bed (block) along x", wide(0), "box-width", c.boxWidth);
    check("the bed (block) along z", wide(2), "box-width", c.boxWidth);
    // A granule's room above the bed's top.
    check("the bed (block) in height", kBedClearance + span(1) + kReach + kReach, "emitter-height",
          c.emitterHeight);
  }
  checkPourSpeed(name(), "emitter-size", emitterHalfExtent(), c.rate, d());
  WorldSettings settings;
  settings.particleDiameter = d();
  kit::reserveExactly(settings, name(), std::uint64_t(c.granules) + bedGranules());
  settings.maxSpeed =
      pourGuardSpeed(emitterSpeed(), c.emitterHeight * d(), gravityMagnitude(settings));
  settings.stepsPerContact = kStepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, c.youngsModulus);
  return settings;
}

void SandBoxPour::build(World& world) {
  m_poured = 0;
  const float height = m_config.boxHeight * d();
  world.addCollider(Box{.center = {0.0f, 0.5f * height, 0.0f},
                        .halfExtents = {halfWidth(), 0.5f * height, halfWidth()},
                        .inside = true});
  const bool bed = bedGranules() > 0;
  const float spacing = kDefaultGranuleSpacing * d();
  const float bedHeight = bed ? kit::blockSpan(m_config.block[1], spacing) : 0.0f;
  if (bed) {
    world.addGranules(GranuleBlock{.center = {0.0f, kBedClearance * d() + 0.5f * bedHeight, 0.0f},
                                   .countX = m_config.block[0],
                                   .countY = m_config.block[1],
                                   .countZ = m_config.block[2],
                                   .spacing = spacing,
                                   .seed = m_config.seed * 1000003u + 1u});  // not the emitter's
  }
  // Calm means nothing while the bed collapses onto the floor (its top layer falls about its own
  // height) or the last granule falls from the emitter; then the sand slides a while. The bed's
  // wait is limited from its drop, the pile's from the pour's end.
  const double g = gravityMagnitude(world.settings());
  const double bedLanding = bed ? 1.5 * fallTime(bedHeight + kBedClearance * d(), 0.0, g) : 0.0;
  m_course = kit::Course(
      {.settleSpeed = m_config.settleSpeed,
       .maxSettleSeconds = m_config.maxSettleSeconds - bedLanding,
       .actAfter = bedLanding,
       .minRestSeconds = 1.5 * fallTime(m_config.emitterHeight * d(), emitterSpeed(), g),
       .maxRestSeconds = m_config.maxSettleSeconds,
       .actFirst = !bed},
      kit::granuleMass(world.settings()));
  if (!bed) startPour(world);
}

void SandBoxPour::startPour(World& world) {
  const float half = emitterHalfExtent();
  world.addEmitter(EmitterSettings{.center = {0.0f, m_config.emitterHeight * d(), 0.0f},
                                   .halfExtentX = half,
                                   .halfExtentZ = half,
                                   .rate = m_config.rate,
                                   .velocity = {0.0f, -emitterSpeed(), 0.0f},
                                   .maxGranules = m_config.granules,
                                   .seed = m_config.seed});
}

void SandBoxPour::update(World& world, const StepReport& report, double simTime) {
  m_poured = world.granulesSpawned() - bedGranules();
  if (m_course.acting() && m_poured >= m_config.granules) m_course.endAct(simTime);
  const bool bedSettling = m_course.phase() == kit::Course::Phase::Settling;
  const std::uint32_t granules = bedGranules() + (bedSettling ? 0u : m_config.granules);
  if (m_course.update(report, simTime, granules) && m_course.acting()) startPour(world);
}

std::string SandBoxPour::status() const {
  return pourStatus(m_course, m_poured, m_config.granules);
}

bool SandBoxPour::contains(const Vec3& centre) const {
  const float half = halfWidth();
  return centre.y >= 0.0f && centre.y <= m_config.boxHeight * d() && std::abs(centre.x) <= half &&
         std::abs(centre.z) <= half;
}

float SandBoxPour::pileHeight(std::span<const BodyState> bodies) const {
  return pileExtent(*this, bodies, kReach * d(), [](const Vec3& p) { return p.y; });
}

float SandBoxPour::footprintRadius(std::span<const BodyState> bodies) const {
  return pileExtent(*this, bodies, kReach * d(),
                    [](const Vec3& p) { return std::hypot(p.x, p.z); });
}

std::vector<SceneMetric> SandBoxPour::metrics(std::span<const BodyState> bodies) const {
  const double height = pileHeight(bodies);
  const double radius = footprintRadius(bodies);
  const double pourEnd = m_course.actEnd();
  return {
      {"granules_poured", static_cast<double>(m_poured)},
      {"granules_budget", static_cast<double>(m_config.granules)},
      {"bed_granules", static_cast<double>(bedGranules())},
      {"pour_rate_per_s", m_config.rate},
      {"pour_seconds", pourEnd >= 0.0 ? pourEnd - m_course.actStart() : 0.0},
      {"emitter_speed_m_per_s", emitterSpeed()},
      {"pile_height_m", height},
      {"pile_height_d", height / d()},
      {"footprint_radius_m", radius},
      {"footprint_radius_d", radius / d()},
      {"box_half_width_m", halfWidth()},
  };
}

SceneBounds SandBoxPour::bounds() const {
  const float half = halfWidth();
  return {{-half, 0.0f, -half}, {half, m_config.boxHeight * d(), half}};
}

}  // namespace sandphys::scenes
