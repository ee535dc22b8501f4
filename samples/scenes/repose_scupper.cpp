#include "scenes/repose_scupper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "scenes/heap_metrics.h"
#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

constexpr float kReach = static_cast<float>(kGranuleReach);
// Thickness of the walls, the gate and the ledge's sides, d.
constexpr float kWall = 2.0f;
// Room between a fill granule at its farthest jitter (along one axis: the walls are
// axis-aligned) and a wall, d.
constexpr float kClearance = 0.2f;
const float kAxisJitter = GranuleBlock{}.jitter * kDefaultGranuleSpacing;
// Walls above the top of the fill's lattice, d.
constexpr float kHeadroom = 4.0f;
// Depth of the sink's top below the sump floor's particle centres, d: past the sump's end a
// grain that deep has left. The sink is kSinkHeight d high and reaches kRunout d past the sump's
// end, where the container's end wall stands.
constexpr float kSinkDepth = 3.0f;
constexpr float kSinkHeight = 10.0f;
constexpr float kRunout = 20.0f;
// The reservoir's lattice (10.7 d³ per granule) settles to about 3.6 d³ per granule, a third of
// its height, so its top granules fall two thirds of it before the gate opens; the speed guard
// covers that fall or the one from the scupper to the sump's floor, whichever is longer.
constexpr float kCollapse = 2.0f / 3.0f;

// Lattice slots across a reservoir `width` d wide (x or z), clear of the walls on either side for
// a granule at its farthest jitter; alternate layers are half a spacing apart, which costs half a
// spacing of the room.
std::uint32_t latticeSlots(float width) {
  const float room = width - 2.0f * (kReach + kAxisJitter + kClearance);
  return static_cast<std::uint32_t>(std::max(
      0.0f, std::floor((room - 0.5f * kDefaultGranuleSpacing) / kDefaultGranuleSpacing) + 1.0f));
}

}  // namespace

std::uint32_t ReposeScupper::rowLength() const {
  return latticeSlots(m_config.reservoirWidth);
}

std::uint32_t ReposeScupper::rowsPerLayer() const {
  return latticeSlots(m_config.depth);
}

std::vector<GranuleBlock> ReposeScupper::fillBlocks() const {
  const std::uint32_t rowLen = rowLength();
  const std::uint32_t rows = rowsPerLayer();
  const std::uint32_t perLayer = rowLen * rows;
  std::vector<GranuleBlock> blocks;
  if (perLayer == 0) return blocks;
  const float spacing = kDefaultGranuleSpacing * d();
  const float centreX = -kWall * d() - 0.5f * m_config.reservoirWidth * d();
  const float firstZ = -0.5f * static_cast<float>(rows - 1) * spacing;
  const float bottom = (m_config.ledge + kReach + kAxisJitter + kClearance) * d();
  std::uint64_t seed = m_config.seed * 1000003u;
  std::uint32_t left = m_config.granules;
  for (std::uint32_t i = 0; left > 0; ++i) {
    const std::uint32_t count = std::min(left, perLayer);
    left -= count;
    const float y = bottom + static_cast<float>(i) * kShiftedLayerHeight * d();
    // Layers alternate a quarter spacing either side of the centre along x and z: half a
    // spacing apart, and each clear of the walls by the same room (latticeSlots).
    const float shift = (i % 2 == 1 ? 0.25f : -0.25f) * spacing;
    const std::uint32_t fullRows = count / rowLen;
    const std::uint32_t rest = count % rowLen;
    if (fullRows > 0) {
      blocks.push_back(GranuleBlock{
          .center = {centreX + shift, y,
                     firstZ + 0.5f * static_cast<float>(fullRows - 1) * spacing + shift},
          .countX = rowLen,
          .countY = 1,
          .countZ = fullRows,
          .spacing = spacing,
          .seed = seed++});
    }
    if (rest > 0) {
      const float firstX = centreX - 0.5f * static_cast<float>(rowLen - 1) * spacing;
      blocks.push_back(
          GranuleBlock{.center = {firstX + 0.5f * static_cast<float>(rest - 1) * spacing + shift, y,
                                  firstZ + static_cast<float>(fullRows) * spacing + shift},
                       .countX = rest,
                       .countY = 1,
                       .countZ = 1,
                       .spacing = spacing,
                       .seed = seed++});
    }
  }
  return blocks;
}

float ReposeScupper::wallTop() const {
  const std::vector<GranuleBlock> blocks = fillBlocks();
  const float top = blocks.empty() ? m_config.ledge * d() : blocks.back().center.y;
  return top + (kReach + kHeadroom) * d();
}

SurfaceMaterial ReposeScupper::wallMaterial() const {
  return {.friction = m_config.wallFriction, .restitution = m_config.restitution};
}

Box ReposeScupper::gate(bool open) const {
  const float bottom = (m_config.ledge + (open ? m_config.outlet : 0.0f)) * d();
  const float top = wallTop() + (open ? m_config.outlet * d() : 0.0f);
  return Box{.center = {-0.5f * kWall * d(), 0.5f * (bottom + top), 0.0f},
             .halfExtents = {0.5f * kWall * d(), 0.5f * (top - bottom),
                             (0.5f * m_config.depth + kWall) * d()},
             .inside = false,
             .material = wallMaterial()};
}

WorldSettings ReposeScupper::worldSettings() const {
  const std::string scene = "repose-scupper: ";
  if (rowLength() == 0 || rowsPerLayer() == 0) {
    throw InvalidArgument(
        scene + "reservoir-width " + numberText(m_config.reservoirWidth) + " d and depth " +
        numberText(m_config.depth) +
        " d leave no room for a granule in the reservoir (each at least " +
        numberText(2.0f * (kReach + kAxisJitter + kClearance) + 0.5f * kDefaultGranuleSpacing) +
        " d)");
  }
  if (m_config.outlet < 2.0f * kReach) {
    throw InvalidArgument(scene + "outlet " + numberText(m_config.outlet) +
                          " d is lower than a granule (at least " + numberText(2.0f * kReach) +
                          " d): no sand can pass the scupper");
  }
  if (m_config.wallMargin * 2.0f >= m_config.depth) {
    throw InvalidArgument(scene + "wall-margin " + numberText(m_config.wallMargin) +
                          " d leaves nothing of the depth " + numberText(m_config.depth) +
                          " d to read the flank from");
  }
  if (!(m_config.minDrainSeconds <= m_config.maxDrainSeconds)) {
    throw InvalidArgument(scene + "min-drain-seconds " + numberText(m_config.minDrainSeconds) +
                          " is more than max-drain-seconds " +
                          numberText(m_config.maxDrainSeconds));
  }
  const std::uint64_t floorParticles = roughFloorParticles(sumpFloor(), d());
  const std::uint64_t particles = 4ull * m_config.granules + floorParticles;
  if (m_config.granules == 0 || particles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(scene + "granules = " + std::to_string(m_config.granules) +
                          " must be >= 1 and, with the sump floor's " +
                          std::to_string(floorParticles) +
                          " particles, fit a World's 2^32 particles");
  }
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.material.restitution = m_config.restitution;
  settings.maxBodies = m_config.granules + 1;  // + the sump's floor
  settings.maxParticles = static_cast<std::uint32_t>(particles);
  // Settling is judged from every frame's kinetic energy.
  settings.statsEachFrame = true;
  const float fillHeight = wallTop() / d() - kHeadroom - m_config.ledge;
  const float fall = std::max(m_config.ledge + m_config.outlet, kCollapse * fillHeight) * d();
  settings.maxSpeed = pourGuardSpeed(0.0f, fall, gravityMagnitude(settings));
  settings.stepsPerContact = m_config.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

RoughFloor ReposeScupper::sumpFloor() const {
  // Particles centred from the ledge's face to the sump's end, half a diameter clear of the side
  // walls.
  return RoughFloor{.center = {0.5f * m_config.sumpLength * d(), 0.0f, 0.0f},
                    .halfExtentX = 0.5f * m_config.sumpLength * d(),
                    .halfExtentZ = 0.5f * (m_config.depth - 1.0f) * d(),
                    .spacing = d()};
}

void ReposeScupper::build(World& world) {
  m_released = false;
  m_finished = false;
  m_calm = false;
  m_releasedAt = -1.0;
  m_finishedAt = -1.0;
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;

  const float top = wallTop();
  const float w = kWall * d();
  const float inside = m_config.reservoirWidth * d();
  const float halfDepth = 0.5f * m_config.depth * d();
  const float far = -(inside + w);  // the reservoir's far wall, x
  const float end = m_config.sumpLength * d();
  const float sinkTop = -kSinkDepth * d();
  const float sinkBottom = sinkTop - kSinkHeight * d();
  const float runoutEnd = end + kRunout * d();
  // One box holds it all: its far side is the reservoir's far wall, its sides along z the side
  // walls of the reservoir and the sump, and it reaches past the sump's end and below its floor
  // far enough for the sink there (the viewer shows an inside box cut away toward the eye).
  world.addCollider(
      Box{.center = {0.5f * (far + runoutEnd), 0.5f * (sinkBottom - d() + top), 0.0f},
          .halfExtents = {0.5f * (runoutEnd - far), 0.5f * (top - sinkBottom + d()), halfDepth},
          .inside = true,
          .material = wallMaterial()});
  // The ledge under the reservoir, down to the box's floor; its top is the reservoir's floor.
  const float ledgeBottom = sinkBottom - 2.0f * d();
  world.addCollider(Box{
      .center = {0.5f * (far - w), 0.5f * (ledgeBottom + m_config.ledge * d()), 0.0f},
      .halfExtents = {0.5f * (w - far), 0.5f * (m_config.ledge * d() - ledgeBottom), halfDepth + w},
      .inside = false,
      .material = wallMaterial()});
  m_gate = world.addCollider(gate(false));
  world.addRoughFloor(sumpFloor());
  // Everything that runs off the sump's end (or, by a fault, through its floor) ends here.
  world.addSink(Sink{.min = {far, sinkBottom, -halfDepth - w},
                     .max = {runoutEnd + w, sinkTop, halfDepth + w}});

  for (const GranuleBlock& block : fillBlocks()) world.addGranules(block);
}

void ReposeScupper::update(World& world, const StepReport& report, double simTime) {
  if (m_finished) return;
  const bool calm =
      granulesCalm(report, report.stats.granulesAlive, m_granuleMass, m_config.settleSpeed);
  if (!m_released) {
    if (!releaseDue(calm, simTime, m_config.releaseTime, m_config.maxSettleSeconds)) return;
    world.setCollider(m_gate, gate(true));
    m_released = true;
    m_releasedAt = simTime;
    return;
  }
  const double draining = simTime - m_releasedAt;
  if ((calm && draining >= m_config.minDrainSeconds) || draining >= m_config.maxDrainSeconds) {
    m_finished = true;
    m_calm = calm;
    m_finishedAt = simTime;
  }
}

std::string ReposeScupper::status() const {
  if (!m_released) return "settling";
  if (!m_finished) return "draining";
  return m_calm ? "settled" : "stopped";
}

bool ReposeScupper::inSump(const Vec3& centre) const {
  return centre.x >= 0.0f && centre.x <= m_config.sumpLength * d() && centre.y >= 0.0f &&
         std::abs(centre.z) <= 0.5f * m_config.depth * d();
}

bool ReposeScupper::inReservoir(const Vec3& centre) const {
  const float w = kWall * d();
  // The scupper (x from -w to 0, where the gate stood) counts as the reservoir.
  return centre.x < 0.0f && centre.x >= -w - m_config.reservoirWidth * d() &&
         centre.y >= m_config.ledge * d() && std::abs(centre.z) <= 0.5f * m_config.depth * d();
}

bool ReposeScupper::contains(const Vec3& centre) const {
  return inSump(centre) || inReservoir(centre);
}

analysis::HeapAngle ReposeScupper::heapAngle(std::span<const BodyState> bodies) const {
  const float zMax = (0.5f * m_config.depth - m_config.wallMargin) * d();
  std::vector<Vec3> centres;
  centres.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && inSump(body.position) && std::abs(body.position.z) <= zMax) {
      centres.push_back(body.position);
    }
  }
  // The pile leans on the ledge's face (x = 0) and falls toward +x; the floor's surface is the
  // top of its particles; cells one granule wide.
  return analysis::angleOfRepose(centres, {.shape = analysis::HeapShape::ridge,
                                           .axisX = 0.0,
                                           .floorY = 0.5 * d(),
                                           .binWidth = 2.0 * kGranuleReach * d(),
                                           .maxRadius = m_config.sumpLength * d()});
}

std::vector<SceneMetric> ReposeScupper::metrics(std::span<const BodyState> bodies) const {
  std::uint32_t sump = 0;
  std::uint32_t reservoir = 0;
  std::uint32_t alive = 0;
  for (const BodyState& body : bodies) {
    if (!body.granule || !body.alive) continue;
    ++alive;
    sump += inSump(body.position) ? 1 : 0;
    reservoir += inReservoir(body.position) ? 1 : 0;
  }
  std::vector<SceneMetric> result{
      {"granules_in_reservoir", static_cast<double>(reservoir)},
      {"granules_in_sump", static_cast<double>(sump)},
      {"granules_lost",
       static_cast<double>(m_config.granules - std::min(m_config.granules, alive))},
      {"release_time_s", m_releasedAt},
      {"end_time_s", m_finishedAt},
      {"friction", m_config.friction},
      {"settled", m_calm ? 1.0 : 0.0},
  };
  appendHeapAngleMetrics(
      result, [&] { return heapAngle(bodies); }, d());
  return result;
}

std::vector<SceneParameter> ReposeScupper::parameters() {
  return {
      {"granules", "granules in the reservoir", &m_config.granules, 1, 1e8},
      {"friction", "Coulomb friction coefficient of the grains and the sump's floor",
       &m_config.friction, 0.0, 10.0},
      {"wall-friction", "Coulomb friction coefficient of the walls, the ledge and the gate",
       &m_config.wallFriction, 0.0, 10.0},
      {"outlet", "height of the open scupper, d", &m_config.outlet, 0.5, 1e4},
      {"depth", "depth of the container across the slot, d", &m_config.depth, 1.0, 1e4},
      {"reservoir-width", "width of the reservoir's inside, d", &m_config.reservoirWidth, 1.0, 1e4},
      {"ledge", "height of the reservoir's floor above the sump's floor, d", &m_config.ledge, 1.0,
       1e4},
      {"sump-length", "length of the sump's floor, d", &m_config.sumpLength, 1.0, 1e4},
      {"wall-margin", "the flank is read this far from the side walls, d", &m_config.wallMargin,
       0.0, 1e4},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"restitution", "coefficient of restitution", &m_config.restitution, 0.01, 1.0},
      {"release-time", "earliest time the scupper opens, s", &m_config.releaseTime, 0.0, 1e9},
      {"settle-speed", "the sand has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the reservoir to settle past release-time, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"min-drain-seconds", "the run ends when calm at least this long after the release, s",
       &m_config.minDrainSeconds, 0.0, 1e6},
      {"max-drain-seconds", "the run ends this long after the release, s",
       &m_config.maxDrainSeconds, 0.0, 1e6},
      {"steps-per-contact", "substeps per Hertz contact time at the speed guard",
       &m_config.stepsPerContact, kMinStepsPerContact, 1e4},
      {"seed", "random seed of the fill", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds ReposeScupper::bounds() const {
  const float halfDepth = 0.5f * m_config.depth * d();
  return {{-(m_config.reservoirWidth + kWall) * d(), -kSinkDepth * d(), -halfDepth},
          {m_config.sumpLength * d(), wallTop(), halfDepth}};
}

}  // namespace sandphys::scenes
