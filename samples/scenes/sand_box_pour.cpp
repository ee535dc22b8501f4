#include "scenes/sand_box_pour.h"

#include "scenes/pour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sandphys::scenes {

namespace {

// kGranuleReach in float, as the scene's geometry is computed.
constexpr float kReach = static_cast<float>(kGranuleReach);

// Height of the bed's lowest granule centres above the floor, d: the granule's reach plus the
// block's jitter (0.03 of 2.4 d), so that no granule starts inside the floor.
constexpr float kBedClearance = 1.4f;

// Substeps per Hertz contact time at the guard speed. The guard is the worst impact; slower
// contacts last longer and so get more substeps. 10 (the minimum is 8) halves the cost of the
// default 20, which a pour of thousands of granules on llvmpipe needs, as the cylinder-pile
// settle test does.
constexpr float kStepsPerContact = 10.0f;

// Granules slower than this (m/s) belong to the pile; the ones falling from the emitter leave it
// at kMinPourSpeed or more and only speed up, so a pile measured during the pour leaves them
// out.
constexpr float kRestSpeed = 0.3f;

// Fraction of a fall's time added before the pile may count as settled: after landing the grains
// still slide and bounce for a while.
constexpr double kLandingMargin = 0.5;

bool atRest(const BodyState& body) {
  const Vec3& v = body.velocity;
  return v.x * v.x + v.y * v.y + v.z * v.z < kRestSpeed * kRestSpeed;
}

}  // namespace

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
  WorldSettings settings;
  settings.particleDiameter = d();
  const std::string scene = "sand-box-pour: ";

  const std::uint64_t granules = static_cast<std::uint64_t>(m_config.granules) + bedGranules();
  if (4 * granules > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(scene + std::to_string(granules) +
                          " granules (bed and pour) are more than a World can index");
  }
  const float boxWidth = m_config.boxWidth;
  if (m_config.emitterSize + 2.0f * kReach > boxWidth) {
    throw InvalidArgument(scene + "emitter-size " + numberText(m_config.emitterSize) +
                          " d does not fit in box-width " + numberText(boxWidth) +
                          " d (it needs the emitter's width plus " + numberText(2.0f * kReach) +
                          " d)");
  }
  if (m_config.emitterHeight + kReach > m_config.boxHeight) {
    throw InvalidArgument(scene + "emitter-height " + numberText(m_config.emitterHeight) +
                          " d is not inside the box (box-height " + numberText(m_config.boxHeight) +
                          " d)");
  }
  if (bedGranules() > 0) {
    const float jitter = 2.0f * GranuleBlock{}.jitter * kDefaultGranuleSpacing;
    for (int axis : {0, 2}) {
      const float extent = static_cast<float>(m_config.block[axis] - 1) * kDefaultGranuleSpacing +
                           jitter + 2.0f * kReach;
      if (extent > boxWidth) {
        throw InvalidArgument(scene + "bed (block) of " + std::to_string(m_config.block[axis]) +
                              " granules along " + (axis == 0 ? "x" : "z") + " is " +
                              numberText(extent) + " d wide, more than box-width " +
                              numberText(boxWidth) + " d");
      }
    }
    const float bedTop =
        kBedClearance + static_cast<float>(m_config.block[1] - 1) * kDefaultGranuleSpacing + kReach;
    if (bedTop + kReach > m_config.emitterHeight) {
      throw InvalidArgument(scene + "bed (block) of " + std::to_string(m_config.block[1]) +
                            " layers reaches " + numberText(bedTop) + " d, into the emitter at " +
                            numberText(m_config.emitterHeight) + " d");
    }
  }
  checkPourSpeed("sand-box-pour", "emitter-size", emitterHalfExtent(), m_config.rate, d());

  settings.maxBodies = static_cast<std::uint32_t>(granules);
  settings.maxParticles = static_cast<std::uint32_t>(4 * granules);
  settings.maxSpeed =
      pourGuardSpeed(emitterSpeed(), m_config.emitterHeight * d(), gravityMagnitude(settings));
  settings.stepsPerContact = kStepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

void SandBoxPour::build(World& world) {
  m_poured = 0;
  m_pourStart = -1.0;
  m_pourEnd = -1.0;
  m_finished = false;
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;

  const float height = m_config.boxHeight * d();
  world.addCollider(Box{.center = {0.0f, 0.5f * height, 0.0f},
                        .halfExtents = {halfWidth(), 0.5f * height, halfWidth()},
                        .inside = true});
  m_bedDropTime = world.simulatedTime();
  if (bedGranules() == 0) {
    startPour(world, world.simulatedTime());
    return;
  }
  const float spacing = kDefaultGranuleSpacing * d();
  const float bedHeight = static_cast<float>(m_config.block[1] - 1) * spacing;
  world.addGranules(GranuleBlock{.center = {0.0f, kBedClearance * d() + 0.5f * bedHeight, 0.0f},
                                 .countX = m_config.block[0],
                                 .countY = m_config.block[1],
                                 .countZ = m_config.block[2],
                                 .spacing = spacing,
                                 // Not the emitter's seed: the bed and the pour differ.
                                 .seed = m_config.seed * 1000003u + 1u});
  // The lattice collapses onto the floor: its top layer falls about its own height.
  const double g = gravityMagnitude(world.settings());
  m_minSettleTime = (1.0 + kLandingMargin) * fallTime(bedHeight + kBedClearance * d(), 0.0, g);
}

void SandBoxPour::startPour(World& world, double simTime) {
  const float half = emitterHalfExtent();
  world.addEmitter(EmitterSettings{.center = {0.0f, m_config.emitterHeight * d(), 0.0f},
                                   .halfExtentX = half,
                                   .halfExtentZ = half,
                                   .rate = m_config.rate,
                                   .velocity = {0.0f, -emitterSpeed(), 0.0f},
                                   .maxGranules = m_config.granules,
                                   .seed = m_config.seed});
  m_pourStart = simTime;
}

void SandBoxPour::update(World& world, const StepReport& report, double simTime) {
  if (m_finished) return;
  auto calm = [&](std::uint32_t granules) {
    return granulesCalm(report, granules, m_granuleMass, m_config.settleSpeed);
  };

  if (m_pourStart < 0.0) {
    const double sinceDrop = simTime - m_bedDropTime;
    if (sinceDrop < m_minSettleTime) return;
    if (!calm(bedGranules()) && sinceDrop < m_config.maxSettleSeconds) return;
    startPour(world, simTime);
    return;
  }

  m_poured = world.granulesSpawned() - bedGranules();
  if (m_poured < m_config.granules) return;
  if (m_pourEnd < 0.0) {
    m_pourEnd = simTime;
    // The last granule left the emitter during this frame and still has to fall onto the pile.
    const double g = gravityMagnitude(world.settings());
    m_minSettleTime =
        (1.0 + kLandingMargin) * fallTime(m_config.emitterHeight * d(), emitterSpeed(), g);
  }
  const double sincePour = simTime - m_pourEnd;
  if (sincePour < m_minSettleTime) return;
  if (!calm(m_config.granules + bedGranules()) && sincePour < m_config.maxSettleSeconds) return;
  m_finished = true;
}

std::string SandBoxPour::status() const {
  if (m_pourStart < 0.0) return "bed settling";
  std::string line = "poured " + std::to_string(m_poured) + "/" + std::to_string(m_config.granules);
  if (m_finished) line += " settled";
  return line;
}

bool SandBoxPour::contains(const Vec3& centre) const {
  const float half = halfWidth();
  return centre.y >= 0.0f && centre.y <= m_config.boxHeight * d() && std::abs(centre.x) <= half &&
         std::abs(centre.z) <= half;
}

float SandBoxPour::pileHeight(std::span<const BodyState> bodies) const {
  std::vector<float> heights;
  heights.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && atRest(body) && contains(body.position)) {
      heights.push_back(body.position.y);
    }
  }
  if (heights.empty()) return 0.0f;
  return percentile(heights, 0.99) + kReach * d();
}

float SandBoxPour::footprintRadius(std::span<const BodyState> bodies) const {
  std::vector<float> radii;
  radii.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && atRest(body) && contains(body.position)) {
      radii.push_back(std::hypot(body.position.x, body.position.z));
    }
  }
  if (radii.empty()) return 0.0f;
  return percentile(radii, 0.99) + kReach * d();
}

std::vector<SceneMetric> SandBoxPour::metrics(std::span<const BodyState> bodies) const {
  const double height = pileHeight(bodies);
  const double radius = footprintRadius(bodies);
  return {
      {"granules_poured", static_cast<double>(m_poured)},
      {"granules_budget", static_cast<double>(m_config.granules)},
      {"bed_granules", static_cast<double>(bedGranules())},
      {"pour_rate_per_s", m_config.rate},
      {"pour_seconds", m_pourEnd >= 0.0 ? m_pourEnd - m_pourStart : 0.0},
      {"emitter_speed_m_per_s", emitterSpeed()},
      {"pile_height_m", height},
      {"pile_height_d", height / d()},
      {"footprint_radius_m", radius},
      {"footprint_radius_d", radius / d()},
      {"box_half_width_m", halfWidth()},
  };
}

std::vector<SceneParameter> SandBoxPour::parameters() {
  return {
      {"rate", "pour rate, granules/s", &m_config.rate, 1.0, 1e5},
      {"granules", "granules poured in total (the emitter's budget)", &m_config.granules, 1, 1e8},
      {"box-width", "inner width of the box along x and z, d", &m_config.boxWidth, 4.0, 1e4},
      {"box-height", "inner height of the box, d", &m_config.boxHeight, 4.0, 1e4},
      {"emitter-height", "height of the emitting rectangle above the floor, d",
       &m_config.emitterHeight, 2.0, 1e4},
      {"emitter-size", "width of the square emitting rectangle, d", &m_config.emitterSize, 0.5,
       1e4},
      {"block", "bed of granules on the floor before the pour, x, y (layers), z; 0,0,0 for none",
       &m_config.block, 0, 1024},
      {"settle-speed", "the pile has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the bed or the pile to settle, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"seed", "random seed of the emitter and the bed", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds SandBoxPour::bounds() const {
  const float half = halfWidth();
  return {{-half, 0.0f, -half}, {half, m_config.boxHeight * d(), half}};
}

}  // namespace sandphys::scenes
