#include "scenes/compression.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

constexpr float kReach = static_cast<float>(kGranuleReach);
// Height of the lattice's lowest granule centres above the floor's particle centres, d: the
// granule's reach, the floor particle's radius and the block's jitter.
constexpr float kClearance = 1.7f;
// Gap between the plunger's rim and the wall, d: narrower than any granule (reach 1.11 d).
constexpr float kPlungerGap = 0.75f;
// The plunger's face: one layer of particles on a triangular lattice this far apart, d, as
// sampleMesh covers a surface by default (kDefaultMeshSpacing: no hole, and it feels smooth).
constexpr float kPlungerSpacing = kDefaultMeshSpacing;
// The plunger waits this far above the settled pile, d.
constexpr float kPlungerStart = 1.0f;
// The wall stands this far above the lattice's top, d.
constexpr float kHeadroom = 6.0f;
// The plunger has touched the sand once the stress under it passes this fraction of maxStress;
// until then it comes down kApproachFactor times faster than plungerSpeed.
constexpr double kContactFraction = 0.005;
constexpr double kApproachFactor = 4.0;
constexpr double kLandingMargin = 0.5;

}  // namespace

std::uint32_t Compression::granulesPerLayer() const {
  return latticeSide() * latticeSide();
}

std::uint32_t Compression::latticeSide() const {
  // A square lattice of spacing s whose granules (reach r) fit in the circle of radius R: its
  // half diagonal ((k - 1) s / 2 + r) √2 <= R.
  const double spacing = kDefaultGranuleSpacing;
  const double room = 2.0 * (m_config.radius / std::numbers::sqrt2 - kReach) / spacing;
  return room < 0.0 ? 0u : 1u + static_cast<std::uint32_t>(std::floor(room));
}

ParticleTemplate Compression::plungerShape() const {
  // Only the face touches the sand. A sampled cylinder (the earlier plunger) had 5880 particles
  // for a pile of 2352 at the default size, most on its caps' thin fan triangles, and made every
  // substep 2.5 times dearer; this disc has about 720.
  const double h = kPlungerSpacing * d();
  const double rowHeight = h * std::numbers::sqrt3 / 2.0;
  const double r = plungerRadius();
  const auto rows = static_cast<std::int64_t>(std::floor(r / rowHeight));
  const auto across = static_cast<std::int64_t>(std::floor(r / h)) + 1;
  std::vector<Vec3> centres;
  for (std::int64_t j = -rows; j <= rows; ++j) {
    const double z = static_cast<double>(j) * rowHeight;
    // Odd rows sit half a spacing over: the lattice's triangles are equilateral.
    const double shift = (j % 2 == 0) ? 0.0 : 0.5 * h;
    for (std::int64_t i = -across; i <= across; ++i) {
      const double x = static_cast<double>(i) * h + shift;
      if (x * x + z * z <= r * r)
        centres.push_back({static_cast<float>(x), 0.0f, static_cast<float>(z)});
    }
  }
  // A kinematic body: its mass only has to be valid.
  return makeParticleTemplate(centres, d(), WorldSettings{}.material.density);
}

double Compression::area() const {
  const double r = m_config.radius * d();
  return std::numbers::pi * r * r;
}

float Compression::plungerRadius() const {
  return (m_config.radius - kPlungerGap) * d();
}

WorldSettings Compression::worldSettings() const {
  const std::string scene = "compression: ";
  const std::uint32_t perLayer = granulesPerLayer();
  if (perLayer == 0) {
    throw InvalidArgument(scene + "radius " + numberText(m_config.radius) +
                          " d holds no granule (at least " +
                          numberText(std::numbers::sqrt2 * kReach) + " d)");
  }
  if (m_config.layers == 0) throw InvalidArgument(scene + "layers must be >= 1");
  if (!(m_config.plungerSpeed > 0.0f) || !(m_config.maxStress > 0.0f)) {
    throw InvalidArgument(scene + "plunger-speed " + numberText(m_config.plungerSpeed) +
                          " m/s and max-stress " + numberText(m_config.maxStress) +
                          " Pa must be > 0");
  }
  const ParticleTemplate plunger = plungerShape();
  const std::uint64_t granules = std::uint64_t(perLayer) * m_config.layers;
  const std::uint64_t particles =
      4 * granules + roughFloorParticles(RoughFloor{.radius = m_config.radius * d()}, d()) +
      plunger.offsets.size();
  if (particles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(scene + std::to_string(granules) + " granules (layers " +
                          std::to_string(m_config.layers) + ") are more than a World can index");
  }
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.maxBodies = static_cast<std::uint32_t>(granules + 2);  // + floor and plunger
  settings.maxParticles = static_cast<std::uint32_t>(particles);
  settings.statsEachFrame = true;
  const float blockHeight =
      (static_cast<float>(m_config.layers) * kDefaultGranuleSpacing + kClearance) * d();
  // The lattice's top falls onto the pile like grains from an emitter at rest.
  settings.maxSpeed = pourGuardSpeed(0.0f, blockHeight, gravityMagnitude(settings));
  settings.stepsPerContact = m_config.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

void Compression::build(World& world) {
  m_phase = Phase::Settling;
  m_touched = false;
  m_turn = 0;
  m_curve.clear();
  m_atRest = {};
  m_atPeak = {};
  m_maxStrain = m_residualStrain = m_peakStress = 0.0;
  m_direction = 0.0;
  m_speed = 0.0;
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;

  const float radius = m_config.radius * d();
  const float spacing = kDefaultGranuleSpacing * d();
  const float blockHeight = static_cast<float>(m_config.layers - 1) * spacing;
  const float wallHeight = (kClearance + kHeadroom) * d() + blockHeight + kReach * d();
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d()});
  world.addCollider(Cylinder{.base = {0.0f, 0.0f, 0.0f}, .radius = radius, .height = wallHeight});
  const std::uint32_t side = latticeSide();
  world.addGranules(GranuleBlock{.center = {0.0f, kClearance * d() + 0.5f * blockHeight, 0.0f},
                                 .countX = side,
                                 .countY = m_config.layers,
                                 .countZ = side,
                                 .spacing = spacing,
                                 .seed = m_config.seed});
  // Parked above the wall until the pile has settled.
  m_bottomY = wallHeight + d();
  m_plunger = world.addBody(
      plungerShape(), BodyDesc{.position = plungerCentre(m_bottomY), .motion = Motion::Kinematic});
  const double g = gravityMagnitude(world.settings());
  m_minSettleTime = (1.0 + kLandingMargin) * fallTime(blockHeight + kClearance * d(), 0.0, g);
}

void Compression::startMove(double direction, double speed, double simTime) {
  m_moveFromY = m_bottomY;
  m_moveStart = simTime;
  m_direction = direction;
  m_speed = speed;
}

void Compression::movePlunger(World& world, double simTime) {
  m_bottomY = m_moveFromY + m_direction * m_speed * (simTime - m_moveStart);
  world.setBodyState(m_plunger,
                     BodyDesc{.position = plungerCentre(m_bottomY),
                              .velocity = {0.0f, static_cast<float>(m_direction * m_speed), 0.0f},
                              .motion = Motion::Kinematic});
}

void Compression::update(World& world, const StepReport& report, double simTime) {
  if (m_phase == Phase::Done) return;
  if (m_phase == Phase::Settling) {
    const std::uint32_t granules = granulesPerLayer() * m_config.layers;
    if (simTime < m_minSettleTime) return;
    if (!granulesCalm(report, granules, m_granuleMass, m_config.settleSpeed) &&
        simTime < m_minSettleTime + m_config.maxSettleSeconds) {
      return;
    }
    m_atRest = {simTime, world.readContacts(), world.readBodies()};
    float top = 0.0f;
    for (const BodyState& body : m_atRest.bodies) {
      if (body.granule && body.alive) top = std::max(top, body.position.y);
    }
    m_bottomY = top + (kReach + kPlungerStart) * d();
    startMove(-1.0, kApproachFactor * m_config.plungerSpeed, simTime);
    m_phase = Phase::Approach;
    world.takeBodyForces();  // from now on
    movePlunger(world, simTime);
    return;
  }

  double force = 0.0;
  for (const BodyForce& f : world.takeBodyForces()) {
    if (f.body == m_plunger) force = f.meanForce().y;
  }
  const double stress = force / area();
  const double floorTop = 0.5 * d();
  auto strain = [&] { return m_touched ? (m_contactY - m_bottomY) / m_height : 0.0; };

  switch (m_phase) {
    case Phase::Approach:
      if (stress > kContactFraction * m_config.maxStress) {
        startMove(-1.0, m_config.plungerSpeed, simTime);
        m_phase = Phase::Preload;
      }
      break;
    case Phase::Preload:
      if (stress >= m_config.preloadFraction * m_config.maxStress) {
        startMove(1.0, m_config.plungerSpeed, simTime);
        m_phase = Phase::Easing;
      }
      break;
    case Phase::Easing:
      if (stress <= 0.0) {
        // The lowest height without compression: the experiment starts here.
        m_touched = true;
        m_contactY = m_bottomY;
        m_height = m_contactY - floorTop;
        m_curve.push_back({0.0, 0.0});
        startMove(-1.0, m_config.plungerSpeed, simTime);
        m_phase = Phase::Loading;
      }
      break;
    case Phase::Loading:
      m_curve.push_back({strain(), stress});
      if (stress >= m_config.maxStress) {
        m_peakStress = stress;
        m_maxStrain = strain();
        m_turn = m_curve.size();
        m_atPeak = {simTime, world.readContacts(), world.readBodies()};
        startMove(1.0, m_config.plungerSpeed, simTime);
        m_phase = Phase::Unloading;
      }
      break;
    case Phase::Unloading:
      m_curve.push_back({strain(), stress});
      // The last strain recorded, until the stress is back at zero.
      m_residualStrain = strain();
      if (stress <= 0.0) {
        startMove(0.0, 0.0, simTime);
        m_phase = Phase::Done;
      }
      break;
    default:
      break;
  }
  movePlunger(world, simTime);
}

double Compression::recoveredFraction() const {
  return m_maxStrain > 0.0 ? (m_maxStrain - m_residualStrain) / m_maxStrain : 0.0;
}

std::string Compression::status() const {
  const double stress = m_curve.empty() ? 0.0 : m_curve.back()[1];
  switch (m_phase) {
    case Phase::Settling:
      return "settling";
    case Phase::Approach:
      return "approach";
    case Phase::Preload:
      return "preload";
    case Phase::Easing:
      return "easing";
    case Phase::Loading:
      return "loading: " + numberText(std::round(stress / 100.0) / 10.0) + " kPa";
    case Phase::Unloading:
      return "unloading: " + numberText(std::round(stress / 100.0) / 10.0) + " kPa";
    case Phase::Done:
      return "done";
  }
  return {};
}

bool Compression::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::hypot(centre.x, centre.z) <= m_config.radius * d();
}

std::vector<SceneMetric> Compression::metrics(std::span<const BodyState> /*bodies*/) const {
  return {
      {"granules", static_cast<double>(granulesPerLayer() * m_config.layers)},
      {"pile_height_d", m_height / d()},
      {"peak_stress_pa", m_peakStress},
      {"max_strain", m_maxStrain},
      {"residual_strain", m_residualStrain},
      {"recovered_fraction", recoveredFraction()},
      {"contacts_at_rest", static_cast<double>(m_atRest.contacts.size())},
      {"contacts_at_peak", static_cast<double>(m_atPeak.contacts.size())},
  };
}

std::vector<SceneSeries> Compression::series() const {
  return {SceneSeries{.name = "stress_strain",
                      .points = m_curve,
                      .derived = {{"max_strain", m_maxStrain},
                                  {"residual_strain", m_residualStrain},
                                  {"recovered_fraction", recoveredFraction()}}}};
}

std::vector<SceneParameter> Compression::parameters() {
  return {
      {"radius", "radius of the cylinder and the rough floor, d", &m_config.radius, 2.0, 1e4},
      {"layers", "layers of the lattice the pile is dropped from", &m_config.layers, 1, 1e5},
      {"plunger-speed", "speed of the plunger, m/s", &m_config.plungerSpeed, 1e-4, 10.0},
      {"max-stress", "mean axial stress at which the plunger turns back, Pa", &m_config.maxStress,
       1.0, 1e9},
      {"preload", "stress that flattens the top first, as a fraction of max-stress",
       &m_config.preloadFraction, 0.0, 1.0},
      {"friction", "Coulomb friction coefficient of every contact", &m_config.friction, 0.0, 10.0},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"settle-speed", "the pile has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the pile to settle, s", &m_config.maxSettleSeconds,
       0.0, 1e6},
      {"steps-per-contact", "substeps per Hertz contact time at the speed guard",
       &m_config.stepsPerContact, kMinStepsPerContact, 1e4},
      {"seed", "random seed of the lattice", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds Compression::bounds() const {
  const float r = m_config.radius * d();
  const float top = (kClearance + kHeadroom + 4.0f) * d() +
                    static_cast<float>(m_config.layers) * kDefaultGranuleSpacing * d();
  return {{-r, 0.0f, -r}, {r, top, r}};
}

}  // namespace sandphys::scenes
