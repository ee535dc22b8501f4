#include "scenes/rock_drop.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include "scenes/eigen_conversions.h"
#include "scenes/kit/checks.h"
#include "scenes/kit/course.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kReach;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Room above the rock when it is let go, d.
constexpr float kHeadroom = 4.0f;
// The moving rock is read back (a sync point) every kCheckSeconds of simulated time, s; it is at
// rest after kCalmChecks calm checks in a row (one calm check can be the top of a bounce).
constexpr double kCheckSeconds = 0.1;
constexpr int kCalmChecks = 2;
// The bed's top is measured over columns kTopColumn d wide, leaving out those within
// kTopWallMargin d of a wall, where the grains lean on it.
constexpr float kTopColumn = 2.0f;
constexpr float kTopWallMargin = 3.0f;
// The rock is turned about y, so that its long axis lies neither along x nor along z, then tilted
// about a horizontal axis between x and z, so that it lands on an edge rather than a face.
constexpr float kYawDegrees = 30.0f;
constexpr Vec3 kTiltAxis{0.8944272f, 0.0f, 0.4472136f};  // (2, 0, 1) normalised

using C = RockDropConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"mesh", &C::mesh, "", 0.0, 0.0, "mesh file of the rock (OBJ, STL, PLY, glTF/GLB)"},
    {"scale", &C::scale, "m per mesh unit", 1e-6, 1e6, "factor on the mesh's coordinates"},
    {"fit", &C::fit, "m", 0.0, 1e3, "largest extent of the rock, in place of scale (0: off)"},
    {"density", &C::density, "kg/m^3", 1.0, 1e5, "density of the rock"},
    {"bed", &C::bed, "", 1, 1024, "granules of the bed along x, y (layers), z (x, z grow to fit)"},
    {"drop-height", &C::dropHeight, "d", 0.0, 1e4, "gap between the bed's top and the rock"},
    {"tilt", &C::tilt, "deg", 0.0, 90.0, "tilt of the rock when let go"},
    {"settle-time", &C::settleTime, "s", 0.0, 1e9, "earliest time the rock is dropped"},
    {"rest-speed", &C::restSpeed, "m/s", 0.0, 10.0, "at rest when no point of the rock is faster"},
    {"max-rest-seconds", &C::maxRestSeconds, "s", 0.0, 1e6, "longest wait for the rock to stop"},
});

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

// The parameters the loaded rock depends on.
using RockKey = std::tuple<std::string, float, float, float, float, float>;
auto rockKey(const RockDropConfig& c) {
  return std::tie(c.mesh, c.scale, c.fit, c.density, c.tilt, c.particleDiameter);
}

Quat dropOrientation(float tilt) {
  return toQuat(Eigen::AngleAxisf(radians(tilt), toEigen(kTiltAxis)) *
                Eigen::AngleAxisf(radians(kYawDegrees), Eigen::Vector3f::UnitY()));
}

// The box around some vertices turned about an origin, relative to it, m.
SceneBounds extentOf(const std::vector<Vec3>& vertices, Quat q = {}, Vec3 origin = {}) {
  SceneBounds extent{{kInfinity, kInfinity, kInfinity}, {-kInfinity, -kInfinity, -kInfinity}};
  for (const Vec3& v : vertices) {
    const Vec3 r = rotate(q, v - origin);
    extent.min = {std::min(extent.min.x, r.x), std::min(extent.min.y, r.y),
                  std::min(extent.min.z, r.z)};
    extent.max = {std::max(extent.max.x, r.x), std::max(extent.max.y, r.y),
                  std::max(extent.max.z, r.z)};
  }
  return extent;
}

float largestExtent(const TriangleMesh& mesh) {
  const SceneBounds extent = extentOf(mesh.vertices);
  const Vec3 size = extent.max - extent.min;
  return std::max({size.x, size.y, size.z});
}

}  // namespace

std::string defaultRockMesh() {
  return SANDPHYS_ASSETS_DIR "/rock.obj";
}

// The mesh as loaded and sampled for one set of parameters (the key), shared by settings() and
// build() so that a run loads the file once.
struct RockDrop::LoadedRock {
  RockKey key;
  TriangleMesh mesh;  // scaled to metres
  SampledMesh sampled;
  Vec3 centreOfMass;  // in the mesh's frame, m
  // Turned as the rock is let go, about its centre of mass: the box and the bed follow it.
  SceneBounds drop;
  SceneBounds turned(const Quat& q) const { return extentOf(mesh.vertices, q, centreOfMass); }
};

std::span<const kit::Param<C>> RockDrop::table() const {
  return kTable;
}

const RockDrop::LoadedRock& RockDrop::loadedRock() const {
  if (m_loaded && m_loaded->key == rockKey(m_config)) return *m_loaded;
  auto rock = std::make_shared<LoadedRock>();
  rock->key = rockKey(m_config);
  // loadMesh and sampleMesh name the file in every MeshError.
  rock->mesh = loadMesh(m_config.mesh);
  // validateMesh guarantees a triangle with an area, so the extent is not zero.
  const float scale =
      m_config.fit > 0.0f ? m_config.fit / largestExtent(rock->mesh) : m_config.scale;
  for (Vec3& v : rock->mesh.vertices) v = v * scale;
  // A closed mesh is filled as well: a grain that gets through the surface layer in a hard
  // landing still meets particles inside instead of an empty shell. An open one has no inside.
  const bool closed = analyseEdges(rock->mesh).closed();
  rock->sampled =
      sampleMesh(rock->mesh, d(), MeshSampling{.fillVolume = closed, .density = m_config.density});
  const auto& com = rock->sampled.massProperties.centreOfMass;
  rock->centreOfMass = {float(com[0]), float(com[1]), float(com[2])};
  rock->drop = rock->turned(dropOrientation(m_config.tilt));

  // The time step is sized for contacts between sand particles; a body lighter than one of them
  // has shorter contacts than the step resolves and would be thrown about.
  const float lightest = tetrahedronTemplate(d(), Material{}.density).mass / 4.0f;
  kit::require(rock->sampled.shape.mass >= lightest, name(), "the rock from '", m_config.mesh,
               "' at scale ", scale, " and density ", m_config.density, " kg/m^3 weighs ",
               rock->sampled.shape.mass, " kg, less than one sand particle (", lightest,
               " kg), which the time step cannot resolve: raise scale (or fit) or density");
  m_loaded = std::move(rock);
  return *m_loaded;
}

const TriangleMesh& RockDrop::rockMesh() const {
  return loadedRock().mesh;
}

Count3 RockDrop::bedCounts() const {
  // The box's inner half width (kit::kLatticeGap beyond the lattice's outer centres) holds
  // everything the rock covers as it is let go, so that it lands on sand, not on a wall.
  const SceneBounds& turned = loadedRock().drop;
  Count3 counts = m_config.bed;
  for (const auto& [axis, reach] : {std::pair{0, std::max(-turned.min.x, turned.max.x)},
                                    std::pair{2, std::max(-turned.min.z, turned.max.z)}}) {
    const float needed = (reach + 0.5f * d()) / d() - kit::kLatticeGap;  // lattice half width, d
    const auto fitting = static_cast<std::uint32_t>(
        std::ceil(std::max(0.0f, 2.0f * needed / kDefaultGranuleSpacing - 1e-4f)) + 1.0f);
    counts[std::size_t(axis)] = std::max(counts[std::size_t(axis)], fitting);
  }
  return counts;
}

float RockDrop::halfWidth(int axis) const {
  const float count = static_cast<float>(bedCounts()[std::size_t(axis)] - 1);
  return (0.5f * count * kDefaultGranuleSpacing + kit::kLatticeGap) * d();
}

float RockDrop::boxHeight() const {
  // The rock is let go above the settled bed, which is never higher than the lattice it started
  // as: that lattice's top is the bound.
  const float latticeTop =
      (kit::kLatticeGap + static_cast<float>(m_config.bed[1] - 1) * kDefaultGranuleSpacing +
       kReach) *
      d();
  const float radius = 0.5f * d();
  const SceneBounds& rock = loadedRock().drop;
  return latticeTop + m_config.dropHeight * d() + radius - rock.min.y + rock.max.y + radius +
         kHeadroom * d();
}

WorldSettings RockDrop::worldSettings() const {
  const LoadedRock& rock = loadedRock();
  const float lowestAtDrop = boxHeight() - kHeadroom * d() - rock.drop.max.y + rock.drop.min.y;
  return kit::worldSettings(name(), d(),
                            {.granules = kit::granuleCount(bedCounts()),
                             .bodies = 1,
                             .particles = rock.sampled.centres.size(),
                             .maxSpeed = kit::fallGuardSpeed(lowestAtDrop),  // to the floor
                             .stepsPerContact = kit::kGuardStepsPerContact});
}

void RockDrop::build(World& world) {
  m_course = kit::Course({.settleSpeed = m_config.settleSpeed,
                          .maxSettleSeconds = m_config.maxSettleSeconds,
                          .actAfter = m_config.settleTime},
                         kit::granuleMass(world.settings()));
  m_run = {};
  m_surfaces.clear();  // the rock's, once dropped
  world.addCollider(kit::containerBox(bounds()));
  world.addGranules(kit::blockAbove(kit::kLatticeGap * d(), bedCounts(),
                                    kDefaultGranuleSpacing * d(), m_config.seed));
}

float RockDrop::bedTopOf(std::span<const ParticleState> particles) const {
  const float radius = 0.5f * d();
  const float cell = kTopColumn * d();
  const float insideX = halfWidth(0) - kTopWallMargin * d();
  const float insideZ = halfWidth(2) - kTopWallMargin * d();
  std::map<std::pair<int, int>, float> columns;
  float highest = 0.0f;
  for (const ParticleState& particle : particles) {
    const Vec3& p = particle.position;
    highest = std::max(highest, p.y + radius);
    if (std::abs(p.x) > insideX || std::abs(p.z) > insideZ) continue;
    const std::pair key{int(std::floor(p.x / cell)), int(std::floor(p.z / cell))};
    float& top = columns.try_emplace(key, p.y + radius).first->second;
    top = std::max(top, p.y + radius);
  }
  std::vector<float> tops;
  for (const auto& [key, top] : columns) tops.push_back(top);
  // A bed too small to have an inside away from the walls: its highest grain is its top.
  return tops.empty() ? highest : kit::percentile(tops, 0.5);
}

void RockDrop::drop(World& world, double simTime) {
  // Before the drop every particle is sand.
  m_run.bedTop = bedTopOf(world.readParticles());
  const LoadedRock& rock = loadedRock();
  const Quat q = dropOrientation(m_config.tilt);
  const float y = m_run.bedTop + m_config.dropHeight * d() + 0.5f * d() - rock.drop.min.y;
  m_run.rock =
      world.addBody(rock.sampled.shape, BodyDesc{.position = {0.0f, y, 0.0f}, .orientation = q});
  m_surfaces = {surfaceOf(m_run.rock, rock.mesh, rock.sampled, BodyMaterial::Stone)};
  m_run.startUp = rotate(conjugate(q), {0.0f, 1.0f, 0.0f});
  m_course.endAct(simTime);
  // The first check after the fall onto the bed: before it the rock is in the air (and calm at
  // the very start).
  m_run.nextCheck =
      simTime + kit::fallTime(m_config.dropHeight * d(), 0.0, length(world.settings().gravity)) +
      kCheckSeconds;
}

void RockDrop::update(World& world, const StepReport& report, double simTime) {
  if (m_run.finished) return;
  if (!dropped()) {
    const auto granules = static_cast<std::uint32_t>(kit::granuleCount(bedCounts()));
    if (m_course.update(report, simTime, granules)) drop(world, simTime);
    return;
  }
  m_run.finished = simTime >= droppedAt() + m_config.maxRestSeconds;
  if (m_run.finished || simTime < m_run.nextCheck) return;
  m_run.nextCheck = simTime + kCheckSeconds;
  const BodyState state = world.readBody(m_run.rock);
  // No point of the rock moves faster than |v| + |ω| · (its farthest particle).
  // Eigen's norms (sums ordered x² + (y² + z²)), as the rest has always been judged.
  const float fastest =
      toEigen(state.velocity).norm() +
      toEigen(state.angularVelocity).norm() * loadedRock().sampled.shape.boundingRadius;
  m_run.calmChecks = fastest < m_config.restSpeed ? m_run.calmChecks + 1 : 0;
  if (m_run.calmChecks == 1) m_run.restedAt = simTime;
  m_run.finished = atRest();
}

bool RockDrop::atRest() const {
  return m_run.calmChecks >= kCalmChecks;
}

std::string RockDrop::status() const {
  if (!dropped()) return "bed settling";
  if (!m_run.finished) return "rock moving";
  const double restedAfter = std::round((m_run.restedAt - droppedAt()) * 100.0) / 100.0;
  if (atRest()) return "rock at rest " + kit::numberText(restedAfter) + " s after the drop";
  return "rock still moving " + kit::numberText(m_config.maxRestSeconds) + " s after the drop";
}

std::vector<SceneBody> RockDrop::bodies(const World& world) const {
  if (!dropped()) return {};
  return {kit::sceneBody("rock", world.readBody(m_run.rock), m_run.startUp)};
}

std::vector<SceneMetric> RockDrop::metrics(std::span<const BodyState> bodies) const {
  const BodyState* rock = kit::findBody(bodies, m_run.rock);
  const LoadedRock& loaded = loadedRock();
  const float extent = largestExtent(loaded.mesh);
  std::vector<SceneMetric> out{
      {"granules", static_cast<double>(std::ranges::distance(kit::granulesIn(bodies)))},
      {"rock_particles", static_cast<double>(loaded.sampled.centres.size())},
      {"rock_surface_particles", static_cast<double>(loaded.sampled.surfaceParticles)},
      {"rock_mass_kg", loaded.sampled.shape.mass},
      {"rock_length_m", extent},
      {"rock_length_d", extent / d()},
      {"rock_dropped", rock ? 1.0 : 0.0},
      {"drop_time_s", droppedAt()},
      {"bed_top_m", m_run.bedTop},
  };
  if (!rock) return out;
  const float lowest = rock->position.y + loaded.turned(rock->orientation).min.y;
  const SceneBody now = kit::sceneBody("rock", *rock, m_run.startUp);
  out.insert(out.end(), {
                            {"rock_lowest_m", lowest},
                            // Positive when the rock's lowest point is below the bed's top.
                            {"rock_rest_depth_m", m_run.bedTop - lowest},
                            {"rock_rest_depth_d", (m_run.bedTop - lowest) / d()},
                            {"rock_height_m", rock->position.y},
                            {"rock_speed_m_per_s", now.speed},
                            {"rock_tilt_deg", now.tiltDegrees},
                            {"rock_at_rest", atRest() ? 1.0 : 0.0},
                            {"time_to_rest_s", atRest() ? m_run.restedAt - droppedAt() : -1.0},
                        });
  return out;
}

SceneBounds RockDrop::bounds() const {
  return {{-halfWidth(0), 0.0f, -halfWidth(2)}, {halfWidth(0), boxHeight(), halfWidth(2)}};
}

}  // namespace sandphys::scenes
