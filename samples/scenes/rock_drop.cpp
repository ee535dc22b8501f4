#include "scenes/rock_drop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include "scenes/eigen_conversions.h"

#ifndef SANDPHYS_ASSETS_DIR
#error \
    "SANDPHYS_ASSETS_DIR (the assets/ folder of the source tree) is set by samples/CMakeLists.txt"
#endif

namespace sandphys::scenes {

namespace {

// kGranuleReach in float, as the scene's geometry is computed.
constexpr float kReach = static_cast<float>(kGranuleReach);
// Largest jitter of a bed granule per axis, d (GranuleBlock::jitter of the default spacing).
const float kJitter = GranuleBlock{}.jitter * kDefaultGranuleSpacing;
// Gap between a wall and the nearest lattice centres, d: the reach and the jitter, with room.
constexpr float kWallGap = 1.4f;
// Height of the bed's lowest granule centres above the floor, d: the same reach and jitter.
constexpr float kBedClearance = 1.4f;
// Room above the rock's highest point when it is let go, d.
constexpr float kHeadroom = 4.0f;

// The speed guard is the speed of a fall from the rock's lowest point at the drop to the floor
// with this margin (rebounds, the rim speed of a spinning rock), and never below kMinGuardSpeed.
constexpr float kGuardMargin = 1.1f;
constexpr float kMinGuardSpeed = 2.0f;
// Substeps per Hertz contact time at the guard speed. The guard is the worst case, slower contacts
// last longer and get more substeps; 10 (the minimum is 8) halves the cost of the default 20, as
// slope-avalanche and sand-box-pour do.
constexpr float kStepsPerContact = 10.0f;

// Simulated time between read-backs of the rock while it moves, s: a sync point, so rarely.
constexpr double kCheckSeconds = 0.1;
// Checks in a row at which the rock must be calm: one calm check can be the top of a bounce.
constexpr int kCalmChecks = 2;

// Columns of the bed whose highest grain surfaces make its top, d wide; the columns within
// kTopWallMargin of a wall are left out, where the grains lean on the wall.
constexpr float kTopColumn = 2.0f;
constexpr float kTopWallMargin = 3.0f;

// The rock is turned about y first, so that its long axis lies neither along x nor along z, then
// tilted about a horizontal axis between x and z, so that it lands on an edge rather than a face.
constexpr float kYawDegrees = 30.0f;
constexpr Vec3 kTiltAxis{0.8944272f, 0.0f, 0.4472136f};  // (2, 0, 1) normalised

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

}  // namespace

// The mesh as loaded and sampled for one set of parameters (the key), shared by settings() and
// build() so that a run loads the file once.
struct RockDrop::LoadedRock {
  std::string path;
  float scale = 0.0f;
  float fit = 0.0f;
  float diameter = 0.0f;
  float meshScale = 0.0f;  // the factor applied: fit's or scale
  float density = 0.0f;
  TriangleMesh mesh;  // scaled to metres
  SampledMesh sampled;
  Vec3 centreOfMass{};  // in the mesh's frame, m
  // The extent turned as the rock is let go, for the tilt it was computed at (dropExtent).
  mutable float extentTilt = std::numeric_limits<float>::quiet_NaN();
  mutable Extent dropExtent{};
};

RockDrop::RockDrop() : RockDrop(Config{}) {}

RockDrop::RockDrop(const Config& config) : m_config(config) {
  if (m_config.mesh.empty()) m_config.mesh = SANDPHYS_ASSETS_DIR "/rock.obj";
}

const RockDrop::LoadedRock& RockDrop::loadedRock() const {
  const LoadedRock* old = m_loaded.get();
  if (old && old->path == m_config.mesh && old->scale == m_config.scale &&
      old->fit == m_config.fit && old->diameter == d() && old->density == m_config.density) {
    return *old;
  }
  // The parameter ranges are checked when they are set from text; a Config set in code is
  // checked here, where a bad value would otherwise surface as a confusing mesh error.
  if (!(m_config.scale > 0.0f) || !std::isfinite(m_config.scale)) {
    throw InvalidArgument("rock-drop: scale = " + numberText(m_config.scale) +
                          " must be finite and > 0 (m per mesh unit)");
  }
  if (!(m_config.fit >= 0.0f) || !std::isfinite(m_config.fit)) {
    throw InvalidArgument("rock-drop: fit = " + numberText(m_config.fit) +
                          " must be finite and >= 0 (m; 0: scale applies)");
  }
  if (!(m_config.density > 0.0f) || !std::isfinite(m_config.density)) {
    throw InvalidArgument("rock-drop: density = " + numberText(m_config.density) +
                          " must be finite and > 0 (kg/m^3)");
  }
  auto rock = std::make_shared<LoadedRock>();
  rock->path = m_config.mesh;
  rock->scale = m_config.scale;
  rock->fit = m_config.fit;
  rock->diameter = d();
  rock->density = m_config.density;
  // loadMesh and sampleMesh name the file in every MeshError.
  rock->mesh = loadMesh(m_config.mesh);
  rock->meshScale = m_config.scale;
  if (m_config.fit > 0.0f) {
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
    Eigen::Vector3f hi = -lo;
    for (const Vec3& v : rock->mesh.vertices) {
      lo = lo.cwiseMin(toEigen(v));
      hi = hi.cwiseMax(toEigen(v));
    }
    // validateMesh guarantees a triangle with an area, so the extent is not zero.
    rock->meshScale = m_config.fit / (hi - lo).maxCoeff();
  }
  const float scale = rock->meshScale;
  for (Vec3& v : rock->mesh.vertices) v = {v.x * scale, v.y * scale, v.z * scale};
  // A closed mesh is filled as well: a grain that gets through the surface layer in a hard
  // landing still meets particles inside instead of an empty shell. An open one has no inside.
  const bool closed = analyseEdges(rock->mesh).closed();
  rock->sampled =
      sampleMesh(rock->mesh, d(), MeshSampling{.fillVolume = closed, .density = m_config.density});
  const auto& com = rock->sampled.massProperties.centreOfMass;
  rock->centreOfMass = {float(com[0]), float(com[1]), float(com[2])};

  // The time step is sized for contacts between sand particles; a body lighter than one of them
  // has shorter contacts than the step resolves and would be thrown about.
  const float lightest = tetrahedronTemplate(d(), Material{}.density).mass / 4.0f;
  if (rock->sampled.shape.mass < lightest) {
    throw InvalidArgument(
        "rock-drop: the rock from '" + m_config.mesh + "' at scale " + numberText(scale) +
        " and density " + numberText(m_config.density) + " kg/m^3 weighs " +
        numberText(rock->sampled.shape.mass) + " kg, less than one sand particle (" +
        numberText(lightest) +
        " kg), which the time step cannot resolve: raise scale (or fit) or density");
  }
  m_loaded = std::move(rock);
  return *m_loaded;
}

const TriangleMesh& RockDrop::rockMesh() const {
  return loadedRock().mesh;
}

std::uint32_t RockDrop::rockParticles() const {
  return static_cast<std::uint32_t>(loadedRock().sampled.centres.size());
}

float RockDrop::meshScale() const {
  return loadedRock().meshScale;
}

Count3 RockDrop::bedCounts() const {
  // The rock, turned as it is let go, must land on sand, not on a wall: the box's inner half
  // width (kWallGap beyond the lattice's outer centres) holds everything it covers.
  const Extent& turned = dropExtent();
  Count3 counts = m_config.bed;
  for (const auto& [axis, reach] : {std::pair{0, std::max(-turned.min.x(), turned.max.x())},
                                    std::pair{2, std::max(-turned.min.z(), turned.max.z())}}) {
    const float needed = (reach + 0.5f * d()) / d() - kWallGap;  // lattice half width, d
    const auto fitting = static_cast<std::uint32_t>(
        std::ceil(std::max(0.0f, 2.0f * needed / kDefaultGranuleSpacing - 1e-4f)) + 1.0f);
    counts[std::size_t(axis)] = std::max(counts[std::size_t(axis)], fitting);
  }
  return counts;
}

std::uint32_t RockDrop::bedGranules() const {
  const Count3 bed = bedCounts();
  return bed[0] * bed[1] * bed[2];
}

float RockDrop::halfWidth(int axis) const {
  const float count = static_cast<float>(bedCounts()[std::size_t(axis)] - 1);
  return (0.5f * count * kDefaultGranuleSpacing + kWallGap) * d();
}

Quat RockDrop::dropOrientation() const {
  return toQuat(Eigen::AngleAxisf(radians(m_config.tilt), toEigen(kTiltAxis)) *
                Eigen::AngleAxisf(radians(kYawDegrees), Eigen::Vector3f::UnitY()));
}

RockDrop::Extent RockDrop::turnedExtent(const Quat& orientation) const {
  const LoadedRock& rock = loadedRock();
  const Eigen::Quaternionf q = toEigen(orientation);
  Extent extent{Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()),
                Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity())};
  for (const Vec3& v : rock.mesh.vertices) {
    const Eigen::Vector3f r = q * (toEigen(v) - toEigen(rock.centreOfMass));
    extent.min = extent.min.cwiseMin(r);
    extent.max = extent.max.cwiseMax(r);
  }
  return extent;
}

const RockDrop::Extent& RockDrop::dropExtent() const {
  const LoadedRock& rock = loadedRock();
  if (rock.extentTilt != m_config.tilt) {
    rock.dropExtent = turnedExtent(dropOrientation());
    rock.extentTilt = m_config.tilt;
  }
  return rock.dropExtent;
}

float RockDrop::rockBelow() const {
  return -dropExtent().min.y();
}

float RockDrop::rockAbove() const {
  return dropExtent().max.y();
}

float RockDrop::boxHeight() const {
  // The rock is let go above the settled bed, which is never higher than the lattice it
  // started as: that lattice's top is the bound.
  const float latticeTop =
      (kBedClearance + static_cast<float>(m_config.bed[1] - 1) * kDefaultGranuleSpacing + kReach) *
      d();
  const float radius = 0.5f * d();
  return latticeTop + m_config.dropHeight * d() + radius + rockBelow() + rockAbove() + radius +
         kHeadroom * d();
}

WorldSettings RockDrop::worldSettings() const {
  WorldSettings settings;
  settings.particleDiameter = d();
  const LoadedRock& rock = loadedRock();

  const std::uint64_t granules = bedGranules();
  const std::uint64_t particles = 4 * granules + rock.sampled.centres.size();
  if (particles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("rock-drop: bed of " + std::to_string(granules) +
                          " granules and a rock of " + std::to_string(rock.sampled.centres.size()) +
                          " particles are " + std::to_string(particles) +
                          " particles, more than a World can index");
  }
  settings.maxBodies = static_cast<std::uint32_t>(granules + 1);
  settings.maxParticles = static_cast<std::uint32_t>(particles);

  const float lowestAtDrop = boxHeight() - kHeadroom * d() - rockAbove() - rockBelow();
  settings.maxSpeed = std::max(
      kMinGuardSpeed, kGuardMargin * std::sqrt(2.0f * gravityMagnitude(settings) * lowestAtDrop));
  settings.stepsPerContact = kStepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings);
  return settings;
}

void RockDrop::build(World& world) {
  m_rock = BodyId{};
  m_droppedAt = -1.0;
  m_bedTop = 0.0f;
  m_startUp = {0.0f, 1.0f, 0.0f};
  m_nextCheck = 0.0;
  m_calmChecks = 0;
  m_restedAt = -1.0;
  m_finished = false;
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;

  const float height = boxHeight();
  world.addCollider(Box{.center = {0.0f, 0.5f * height, 0.0f},
                        .halfExtents = {halfWidth(0), 0.5f * height, halfWidth(2)},
                        .inside = true});
  const float spacing = kDefaultGranuleSpacing * d();
  const Count3 bed = bedCounts();
  const float bedHeight = static_cast<float>(bed[1] - 1) * spacing;
  world.addGranules(GranuleBlock{.center = {0.0f, kBedClearance * d() + 0.5f * bedHeight, 0.0f},
                                 .countX = bed[0],
                                 .countY = bed[1],
                                 .countZ = bed[2],
                                 .spacing = spacing,
                                 .seed = m_config.seed});
}

void RockDrop::update(World& world, const StepReport& report, double simTime) {
  if (m_finished) return;
  const double g = gravityMagnitude(world.settings());
  if (!dropped()) {
    if (simTime < m_config.settleTime) return;
    const bool calm = granulesCalm(report, bedGranules(), m_granuleMass, m_config.settleSpeed);
    if (!calm && simTime < m_config.settleTime + m_config.maxSettleSeconds) return;

    // The bed's top: one read-back, at the drop only. Before the drop every particle is sand.
    const float radius = 0.5f * d();
    const float cell = kTopColumn * d();
    const float insideX = halfWidth(0) - kTopWallMargin * d();
    const float insideZ = halfWidth(2) - kTopWallMargin * d();
    std::map<std::pair<int, int>, float> columns;
    float highest = 0.0f;
    for (const ParticleState& particle : world.readParticles()) {
      const Vec3& p = particle.position;
      highest = std::max(highest, p.y + radius);
      if (std::abs(p.x) > insideX || std::abs(p.z) > insideZ) continue;
      const std::pair key{int(std::floor(p.x / cell)), int(std::floor(p.z / cell))};
      auto [it, inserted] = columns.try_emplace(key, p.y + radius);
      if (!inserted) it->second = std::max(it->second, p.y + radius);
    }
    std::vector<float> tops;
    for (const auto& [key, top] : columns) tops.push_back(top);
    // A bed too small to have an inside away from the walls: its highest grain is its top.
    m_bedTop = tops.empty() ? highest : percentile(tops, 0.5);

    const LoadedRock& rock = loadedRock();
    const Quat q = dropOrientation();
    const float y = m_bedTop + m_config.dropHeight * d() + radius + rockBelow();
    m_rock =
        world.addBody(rock.sampled.shape, BodyDesc{.position = {0.0f, y, 0.0f}, .orientation = q});
    m_startUp = toVec3(toEigen(q).conjugate() * Eigen::Vector3f::UnitY());
    m_droppedAt = simTime;
    // The first check after the fall onto the bed: before it the rock is in the air (and calm
    // at the very start).
    m_nextCheck = simTime + fallTime(m_config.dropHeight * d(), 0.0, g) + kCheckSeconds;
    return;
  }

  if (simTime >= m_droppedAt + m_config.maxRestSeconds) {
    m_finished = true;
    return;
  }
  if (simTime < m_nextCheck) return;
  m_nextCheck = simTime + kCheckSeconds;
  const BodyState state = world.readBody(m_rock);
  // No point of the rock moves faster than |v| + |ω| · (its farthest particle).
  const float fastest =
      toEigen(state.velocity).norm() +
      toEigen(state.angularVelocity).norm() * loadedRock().sampled.shape.boundingRadius;
  if (fastest >= m_config.restSpeed) {
    m_calmChecks = 0;
    return;
  }
  if (m_calmChecks++ == 0) m_restedAt = simTime;
  if (m_calmChecks >= kCalmChecks) m_finished = true;
}

std::string RockDrop::status() const {
  if (!dropped()) return "bed settling";
  if (!m_finished) return "rock moving";
  if (m_calmChecks >= kCalmChecks) {
    return "rock at rest " + numberText(std::round((m_restedAt - m_droppedAt) * 100.0) / 100.0) +
           " s after the drop";
  }
  return "rock still moving " + numberText(m_config.maxRestSeconds) + " s after the drop";
}

bool RockDrop::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && centre.y <= boxHeight() && std::abs(centre.x) <= halfWidth(0) &&
         std::abs(centre.z) <= halfWidth(2);
}

Vec3 RockDrop::toRockFrame(const BodyState& state, const Vec3& point) const {
  return toVec3(toEigen(state.orientation).conjugate() *
                    (toEigen(point) - toEigen(state.position)) +
                toEigen(loadedRock().centreOfMass));
}

float RockDrop::lowestPoint(const BodyState& state) const {
  return state.position.y + turnedExtent(state.orientation).min.y();
}

std::vector<SceneBody> RockDrop::bodies(const World& world) const {
  if (!dropped()) return {};
  const BodyState state = world.readBody(m_rock);
  const float up = std::clamp((toEigen(state.orientation) * toEigen(m_startUp)).y(), -1.0f, 1.0f);
  return {{.name = "rock",
           .position = state.position,
           .orientation = state.orientation,
           .speed = toEigen(state.velocity).norm(),
           .tiltDegrees = std::acos(up) * 180.0f / std::numbers::pi_v<float>}};
}

std::vector<SceneMetric> RockDrop::metrics(std::span<const BodyState> bodies) const {
  std::uint32_t granules = 0;
  const BodyState* rock = nullptr;
  for (const BodyState& body : bodies) {
    if (body.granule && body.alive) ++granules;
    if (dropped() && body.index == m_rock.index) rock = &body;
  }
  const LoadedRock& loaded = loadedRock();
  float extent = 0.0f;
  for (int axis = 0; axis < 3; ++axis) {
    float lo = std::numeric_limits<float>::infinity();
    float hi = -lo;
    for (const Vec3& v : loaded.mesh.vertices) {
      const float c = axis == 0 ? v.x : axis == 1 ? v.y : v.z;
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    extent = std::max(extent, hi - lo);
  }
  std::vector<SceneMetric> out{
      {"granules", static_cast<double>(granules)},
      {"rock_particles", static_cast<double>(loaded.sampled.centres.size())},
      {"rock_surface_particles", static_cast<double>(loaded.sampled.surfaceParticles)},
      {"rock_mass_kg", loaded.sampled.shape.mass},
      {"rock_length_m", extent},
      {"rock_length_d", extent / d()},
      {"rock_dropped", rock ? 1.0 : 0.0},
      {"drop_time_s", m_droppedAt},
      {"bed_top_m", m_bedTop},
  };
  if (!rock) return out;
  const float lowest = lowestPoint(*rock);
  const float up = std::clamp((toEigen(rock->orientation) * toEigen(m_startUp)).y(), -1.0f, 1.0f);
  const bool atRest = m_finished && m_calmChecks >= kCalmChecks;
  out.insert(out.end(), {
                            {"rock_lowest_m", lowest},
                            // Positive when the rock's lowest point is below the bed's top.
                            {"rock_rest_depth_m", m_bedTop - lowest},
                            {"rock_rest_depth_d", (m_bedTop - lowest) / d()},
                            {"rock_height_m", rock->position.y},
                            {"rock_speed_m_per_s", toEigen(rock->velocity).norm()},
                            {"rock_tilt_deg", std::acos(up) * 180.0 / std::numbers::pi},
                            {"rock_at_rest", atRest ? 1.0 : 0.0},
                            {"time_to_rest_s", atRest ? m_restedAt - m_droppedAt : -1.0},
                        });
  return out;
}

std::vector<SceneParameter> RockDrop::parameters() {
  return {
      {"mesh", "mesh file of the rock (OBJ, STL, PLY, glTF/GLB)", &m_config.mesh},
      {"scale", "factor on the mesh's coordinates, m per mesh unit", &m_config.scale, 1e-6, 1e6},
      {"fit", "largest extent of the rock, m (scales the mesh to it in place of scale; 0: off)",
       &m_config.fit, 0.0, 1e3},
      {"density", "density of the rock, kg/m^3", &m_config.density, 1.0, 1e5},
      {"bed", "granules of the sand bed along x, y (layers), z (x and z grow to fit the rock)",
       &m_config.bed, 1, 1024},
      {"drop-height", "gap between the settled bed's top and the rock when let go, d",
       &m_config.dropHeight, 0.0, 1e4},
      {"tilt", "tilt of the rock when let go, degrees", &m_config.tilt, 0.0, 90.0},
      {"settle-time", "earliest time the rock is dropped, s", &m_config.settleTime, 0.0, 1e9},
      {"settle-speed", "the bed has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the bed to settle past settle-time, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"rest-speed", "the rock is at rest when no point of it moves faster, m/s",
       &m_config.restSpeed, 0.0, 10.0},
      {"max-rest-seconds", "longest wait for the rock to stop after the drop, s",
       &m_config.maxRestSeconds, 0.0, 1e6},
      {"seed", "random seed of the bed", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds RockDrop::bounds() const {
  return {{-halfWidth(0), 0.0f, -halfWidth(2)}, {halfWidth(0), boxHeight(), halfWidth(2)}};
}

}  // namespace sandphys::scenes
