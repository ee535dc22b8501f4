#include "scenes/dunes.h"

#include "scenes/kit/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

// Depth of the sink's top below the floor's particle centres, d.
constexpr float kSinkDepth = 3.0f;
// kGranuleReach in float, as the scene's geometry is computed.
constexpr float kReach = static_cast<float>(kGranuleReach);

}  // namespace

float Dunes::emitterSpeed() const {
  return pourSpeed(0.5f * m_config.outlet * d(), m_config.rate, d());
}

WorldSettings Dunes::worldSettings() const {
  const std::string scene = "dunes: ";
  // A RoughFloor rectangle has a particle every d from -half to +half along each side; at most
  // this many (World::addRoughFloor rounds each half down to whole spacings).
  const std::uint64_t floorParticles =
      static_cast<std::uint64_t>(2.0 * std::floor(m_config.floorHalfLength) + 1.0) *
      static_cast<std::uint64_t>(2.0 * std::floor(m_config.floorHalfWidth) + 1.0);
  const std::uint64_t granules = 2ull * m_config.granules;
  if (m_config.granules == 0 ||
      4 * granules + floorParticles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(scene + "granules = " + std::to_string(m_config.granules) +
                          " per column must be >= 1 and, with the floor's particles, fit a "
                          "World's 2^32 particles");
  }
  const float reach = 0.5f * m_config.separation + 0.5f * m_config.outlet + kReach;
  if (reach > m_config.floorHalfLength ||
      0.5f * m_config.outlet + kReach > m_config.floorHalfWidth) {
    throw InvalidArgument(scene + "the columns (separation " + numberText(m_config.separation) +
                          " d, outlet " + numberText(m_config.outlet) +
                          " d) reach past the floor (floor-half-length " +
                          numberText(m_config.floorHalfLength) + " d, floor-half-width " +
                          numberText(m_config.floorHalfWidth) + " d)");
  }
  if (m_config.pourHeight < 2.0f * kReach) {
    throw InvalidArgument(scene + "pour-height " + numberText(m_config.pourHeight) +
                          " d leaves no room for a granule above the floor (at least " +
                          numberText(2.0f * kReach) + " d)");
  }
  checkPourSpeed("dunes", "the outlet", 0.5f * m_config.outlet * d(), m_config.rate, d());
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.maxBodies = static_cast<std::uint32_t>(granules + 1);  // + the floor
  settings.maxParticles = static_cast<std::uint32_t>(4 * granules + floorParticles);
  settings.statsEachFrame = true;
  settings.maxSpeed =
      pourGuardSpeed(emitterSpeed(), m_config.pourHeight * d(), gravityMagnitude(settings));
  settings.stepsPerContact = m_config.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

void Dunes::build(World& world) {
  m_poured = 0;
  m_profile = {};
  m_course = kit::Course(pourCourse(fallTime(m_config.pourHeight * d(), emitterSpeed(),
                                             gravityMagnitude(world.settings())),
                                    m_config.settleSpeed, m_config.maxSettleSeconds),
                         kit::granuleMass(world.settings()));
  const float halfX = m_config.floorHalfLength * d();
  const float halfZ = m_config.floorHalfWidth * d();
  world.addRoughFloor(RoughFloor{
      .center = {0.0f, 0.0f, 0.0f}, .halfExtentX = halfX, .halfExtentZ = halfZ, .spacing = d()});
  const float wide = std::max(halfX, halfZ) + m_config.pourHeight * d();
  world.addSink(Sink{.min = {-wide, -(kSinkDepth + 10.0f) * d(), -wide},
                     .max = {wide, -kSinkDepth * d(), wide}});
  const float half = 0.5f * m_config.outlet * d();
  for (int side : {-1, 1}) {
    world.addEmitter(
        EmitterSettings{.center = {static_cast<float>(side) * 0.5f * m_config.separation * d(),
                                   m_config.pourHeight * d(), 0.0f},
                        .halfExtentX = half,
                        .halfExtentZ = half,
                        .rate = m_config.rate,
                        .velocity = {0.0f, -emitterSpeed(), 0.0f},
                        .maxGranules = m_config.granules,
                        // Two different streams of orientations.
                        .seed = m_config.seed * 2 + (side > 0 ? 1 : 0)});
  }
}

void Dunes::update(World& world, const StepReport& report, double simTime) {
  if (m_course.done()) return;
  m_poured = world.granulesSpawned();
  if (m_course.acting() && m_poured >= 2 * m_config.granules) m_course.endAct(simTime);
  if (!m_course.update(report, simTime)) return;
  // Once per run: the settled sand's profile for series().
  m_profile = profile(world.readBodies());
}

std::string Dunes::status() const {
  return pourStatus(m_course, m_poured, 2 * m_config.granules);
}

bool Dunes::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::abs(centre.x) <= m_config.floorHalfLength * d() &&
         std::abs(centre.z) <= m_config.floorHalfWidth * d();
}

Dunes::Profile Dunes::profile(std::span<const BodyState> bodies) const {
  // Strips one granule wide along x; the granules within a granule of the z = 0 plane.
  const double strip = 2.0 * kGranuleReach * d();
  const double halfLength = m_config.floorHalfLength * d();
  const auto strips = static_cast<std::size_t>(std::ceil(2.0 * halfLength / strip));
  const double floorTop = 0.5 * d();
  std::vector<double> top(strips, -1.0);
  std::vector<double> where(strips, 0.0);
  for (const BodyState& body : bodies) {
    if (!body.alive || !body.granule || !contains(body.position)) continue;
    if (std::abs(body.position.z) > strip) continue;
    const auto i =
        std::min(strips - 1, static_cast<std::size_t>((body.position.x + halfLength) / strip));
    const double h = body.position.y - floorTop;
    if (h > top[i]) {
      top[i] = h;
      where[i] = body.position.x;
    }
  }
  Profile p;
  for (std::size_t i = 0; i < strips; ++i) {
    if (top[i] >= 0.0) p.points.push_back({where[i], top[i]});
  }
  for (const auto& point : p.points) {
    auto& crest = point[0] < 0.0 ? p.leftCrest : p.rightCrest;
    if (point[1] > crest[1]) crest = point;
  }
  p.saddle = {0.0, std::numeric_limits<double>::infinity()};
  for (const auto& point : p.points) {
    if (point[0] > p.leftCrest[0] && point[0] < p.rightCrest[0] && point[1] < p.saddle[1]) {
      p.saddle = point;
    }
  }
  if (!std::isfinite(p.saddle[1])) p.saddle = {0.0, 0.0};
  return p;
}

std::vector<SceneMetric> Dunes::metrics(std::span<const BodyState> bodies) const {
  const Profile p = profile(bodies);
  std::uint32_t onFloor = 0;
  for (const BodyState& body : bodies) {
    if (body.granule && body.alive && contains(body.position)) ++onFloor;
  }
  const double lowerCrest = std::min(p.leftCrest[1], p.rightCrest[1]);
  return {
      {"granules_poured", static_cast<double>(m_poured)},
      {"granules_on_floor", static_cast<double>(onFloor)},
      {"left_crest_height_d", p.leftCrest[1] / d()},
      {"left_crest_x_d", p.leftCrest[0] / d()},
      {"right_crest_height_d", p.rightCrest[1] / d()},
      {"right_crest_x_d", p.rightCrest[0] / d()},
      {"saddle_height_d", p.saddle[1] / d()},
      {"saddle_x_d", p.saddle[0] / d()},
      {"saddle_depth_d", (lowerCrest - p.saddle[1]) / d()},
      {"crest_separation_d", (p.rightCrest[0] - p.leftCrest[0]) / d()},
      {"settled", m_course.calm() ? 1.0 : 0.0},
  };
}

std::vector<SceneSeries> Dunes::series() const {
  SceneSeries profile{.name = "dune_profile"};
  for (const auto& point : m_profile.points)
    profile.points.push_back({point[0] / d(), point[1] / d()});
  return {profile};
}

std::vector<SceneParameter> Dunes::parameters() {
  return {
      {"granules", "granules poured by each column", &m_config.granules, 1, 1e8},
      {"separation", "distance between the two columns, d", &m_config.separation, 0.0, 1e4},
      {"friction", "Coulomb friction coefficient of every contact", &m_config.friction, 0.0, 10.0},
      {"outlet", "width of each emitter's square, d", &m_config.outlet, 0.5, 1e4},
      {"rate", "pour rate of each column, granules/s", &m_config.rate, 1.0, 1e5},
      {"pour-height", "height of the emitters above the floor, d", &m_config.pourHeight, 1.0, 1e4},
      {"floor-half-length", "half length of the rough floor along x, d", &m_config.floorHalfLength,
       2.0, 1e4},
      {"floor-half-width", "half width of the rough floor along z, d", &m_config.floorHalfWidth,
       2.0, 1e4},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"settle-speed", "the sand has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the sand to settle after the pour, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"steps-per-contact", "substeps per Hertz contact time at the speed guard",
       &m_config.stepsPerContact, kMinStepsPerContact, 1e4},
      {"seed", "random seed of the emitters", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds Dunes::bounds() const {
  const float x = m_config.floorHalfLength * d();
  const float z = m_config.floorHalfWidth * d();
  return {{-x, -kSinkDepth * d(), -z}, {x, (m_config.pourHeight + 1.0f) * d(), z}};
}

}  // namespace sandphys::scenes
