#include "scenes/repose_scupper.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes/heap_metrics.h"
#include "scenes/kit/checks.h"
#include "scenes/kit/gated_fill.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kJitter;
using kit::kReach;
// In d. Walls, the gate and the ledge's sides are kWall thick; a fill granule's centre stays
// kReach + kJitter + kFillClearance clear of them (the jitter along one axis: the walls are
// axis-aligned), and the walls stand kHeadroom above the fill.
constexpr float kWall = 2.0f;
constexpr float kHeadroom = 4.0f;
// In d. The sink's top lies kSinkDepth below the sump floor's centres, where a grain past the
// sump's end has left; it is kSinkHeight high and reaches kRunout past the sump's end.
constexpr float kSinkDepth = 3.0f;
constexpr float kSinkHeight = 10.0f;
constexpr float kRunout = 20.0f;
// The loose lattice settles to about a third of its height before the gate opens: its top falls
// two thirds of it, which the speed guard covers.
constexpr float kCollapse = 2.0f / 3.0f;

using C = ReposeScupperConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"granules", &C::granules, "", 1, 1e8, "granules in the reservoir"},
    {"friction", &C::friction, "", 0.0, 10.0,
     "Coulomb friction coefficient of the grains and the sump's floor"},
    {"wall-friction", &C::wallFriction, "", 0.0, 10.0,
     "Coulomb friction coefficient of the walls, the ledge and the gate"},
    {"outlet", &C::outlet, "d", 0.5, 1e4, "height of the open scupper"},
    {"depth", &C::depth, "d", 1.0, 1e4, "depth of the container across the slot"},
    {"reservoir-width", &C::reservoirWidth, "d", 1.0, 1e4, "width of the reservoir's inside"},
    {"ledge", &C::ledge, "d", 1.0, 1e4, "height of the reservoir's floor above the sump's floor"},
    {"sump-length", &C::sumpLength, "d", 1.0, 1e4, "length of the sump's floor"},
    {"wall-margin", &C::wallMargin, "d", 0.0, 1e4,
     "the flank is read this far from the side walls"},
    {"release-time", &C::releaseTime, "s", 0.0, 1e9, "earliest time the scupper opens"},
    {"min-drain-seconds", &C::minDrainSeconds, "s", 0.0, 1e6,
     "the run ends when calm at least this long after the release"},
    {"max-drain-seconds", &C::maxDrainSeconds, "s", 0.0, 1e6,
     "the run ends this long after the release"},
});

// Lattice slots across a reservoir `width` d wide, clear of the walls on either side; alternate
// layers are half a spacing apart, which costs half a spacing of the room.
std::uint32_t latticeSlots(float width) {
  const float room = width - 2.0f * (kReach + kJitter + kit::kFillClearance);
  return static_cast<std::uint32_t>(std::max(
      0.0f, std::floor((room - 0.5f * kDefaultGranuleSpacing) / kDefaultGranuleSpacing) + 1.0f));
}

}  // namespace

std::span<const kit::Param<C>> ReposeScupper::table() const {
  return kTable;
}

std::vector<GranuleBlock> ReposeScupper::fillBlocks() const {
  const std::uint32_t rowLen = latticeSlots(m_config.reservoirWidth);
  const std::uint32_t rows = latticeSlots(m_config.depth);
  const std::uint32_t perLayer = rowLen * rows;
  if (perLayer == 0) return {};
  kit::FillBlocks fill(m_config.granules, m_config.seed);
  const float spacing = kDefaultGranuleSpacing * d();
  const float centreX = -kWall * d() - 0.5f * m_config.reservoirWidth * d();
  const float firstX = centreX - 0.5f * static_cast<float>(rowLen - 1) * spacing;
  const float firstZ = -0.5f * static_cast<float>(rows - 1) * spacing;
  const float bottom = (m_config.ledge + kReach + kJitter + kit::kFillClearance) * d();
  for (std::uint32_t i = 0; fill.left() > 0; ++i) {
    const std::uint32_t count = std::min(fill.left(), perLayer);
    const float y = bottom + static_cast<float>(i) * kit::kShiftedLayerHeight * d();
    // Layers alternate a quarter spacing either side of the centre along x and z: half a spacing
    // apart, each clear of the walls by the same room.
    const float shift = (i % 2 == 1 ? 0.25f : -0.25f) * spacing;
    const std::uint32_t fullRows = count / rowLen;
    const std::uint32_t rest = count % rowLen;
    if (fullRows > 0) {
      fill.add({.center = {centreX + shift, y,
                           firstZ + 0.5f * static_cast<float>(fullRows - 1) * spacing + shift},
                .countX = rowLen,
                .countY = 1,
                .countZ = fullRows,
                .spacing = spacing});
    }
    if (rest > 0) {
      fill.add({.center = {firstX + 0.5f * static_cast<float>(rest - 1) * spacing + shift, y,
                           firstZ + static_cast<float>(fullRows) * spacing + shift},
                .countX = rest,
                .countY = 1,
                .countZ = 1,
                .spacing = spacing});
    }
  }
  return fill.blocks();
}

float ReposeScupper::wallTop() const {
  const std::vector<GranuleBlock> blocks = fillBlocks();
  const float top = blocks.empty() ? m_config.ledge * d() : blocks.back().center.y;
  return top + (kReach + kHeadroom) * d();
}

Box ReposeScupper::gate(bool open) const {
  const float bottom = (m_config.ledge + (open ? m_config.outlet : 0.0f)) * d();
  const float top = wallTop() + (open ? m_config.outlet * d() : 0.0f);
  return Box{.center = {-0.5f * kWall * d(), 0.5f * (bottom + top), 0.0f},
             .halfExtents = {0.5f * kWall * d(), 0.5f * (top - bottom),
                             (0.5f * m_config.depth + kWall) * d()},
             .inside = false,
             .material = kit::wallMaterial(m_config)};
}

RoughFloor ReposeScupper::sumpFloor() const {
  // From the ledge's face to the sump's end, half a diameter clear of the side walls.
  return RoughFloor{.center = {0.5f * m_config.sumpLength * d(), 0.0f, 0.0f},
                    .halfExtentX = 0.5f * m_config.sumpLength * d(),
                    .halfExtentZ = 0.5f * (m_config.depth - 1.0f) * d(),
                    .spacing = d()};
}

WorldSettings ReposeScupper::worldSettings() const {
  const Config& c = m_config;
  kit::require(latticeSlots(c.reservoirWidth) > 0 && latticeSlots(c.depth) > 0, name(),
               "reservoir-width ", c.reservoirWidth, " d and depth ", c.depth,
               " d leave no room for a granule in the reservoir (each at least ",
               2.0f * (kReach + kJitter + kit::kFillClearance) + 0.5f * kDefaultGranuleSpacing,
               " d)");
  kit::require(c.outlet >= 2.0f * kReach, name(), "outlet ", c.outlet,
               " d is lower than a granule (at least ", 2.0f * kReach,
               " d): no sand can pass the scupper");
  kit::require(c.wallMargin * 2.0f < c.depth, name(), "wall-margin ", c.wallMargin,
               " d leaves nothing of the depth ", c.depth, " d to read the flank from");
  kit::require(c.minDrainSeconds <= c.maxDrainSeconds, name(), "min-drain-seconds ",
               c.minDrainSeconds, " is more than max-drain-seconds ", c.maxDrainSeconds);
  const float fillHeight = wallTop() / d() - kHeadroom - c.ledge;
  const float fall = std::max(c.ledge + c.outlet, kCollapse * fillHeight) * d();
  kit::SettingsRule rule = kit::gatedFillRule(c, c.granules, fall);
  rule.bodies = 1;
  rule.particles = roughFloorParticles(sumpFloor(), d());
  return kit::worldSettings(name(), d(), rule);
}

void ReposeScupper::build(World& world) {
  m_course = kit::gateCourse(m_config, world.settings(), m_config.minDrainSeconds,
                             m_config.maxDrainSeconds);
  m_endTime = -1.0;
  const SurfaceMaterial wall = kit::wallMaterial(m_config);
  const float top = wallTop();
  const float w = kWall * d();
  const float halfDepth = 0.5f * m_config.depth * d();
  const float far = -(m_config.reservoirWidth * d() + w);  // the reservoir's far wall, x
  const float sinkTop = -kSinkDepth * d();
  const float sinkBottom = sinkTop - kSinkHeight * d();
  const float runoutEnd = m_config.sumpLength * d() + kRunout * d();
  // One box holds it all: the reservoir's far wall, the side walls, and room past the sump's end
  // and below its floor for the sink.
  world.addCollider(
      Box{.center = {0.5f * (far + runoutEnd), 0.5f * (sinkBottom - d() + top), 0.0f},
          .halfExtents = {0.5f * (runoutEnd - far), 0.5f * (top - sinkBottom + d()), halfDepth},
          .inside = true,
          .material = wall});
  // The ledge under the reservoir, down to the box's floor.
  const float ledgeBottom = sinkBottom - 2.0f * d();
  world.addCollider(Box{
      .center = {0.5f * (far - w), 0.5f * (ledgeBottom + m_config.ledge * d()), 0.0f},
      .halfExtents = {0.5f * (w - far), 0.5f * (m_config.ledge * d() - ledgeBottom), halfDepth + w},
      .inside = false,
      .material = wall});
  m_gate = world.addCollider(gate(false));
  world.addRoughFloor(sumpFloor());
  world.addSink(Sink{.min = {far, sinkBottom, -halfDepth - w},
                     .max = {runoutEnd + w, sinkTop, halfDepth + w}});
  for (const GranuleBlock& block : fillBlocks()) world.addGranules(block);
}

void ReposeScupper::update(World& world, const StepReport& report, double simTime) {
  if (!m_course.update(report, simTime)) return;
  if (m_course.done()) {
    m_endTime = simTime;
    return;
  }
  world.setCollider(m_gate, gate(true));
  m_course.endAct(simTime);
}

std::string ReposeScupper::status() const {
  if (m_course.done()) return m_course.calm() ? "settled" : "stopped";
  return releasedAt() < 0.0 ? "settling" : "draining";
}

bool ReposeScupper::inSump(const Vec3& centre) const {
  return centre.x >= 0.0f && centre.x <= m_config.sumpLength * d() && centre.y >= 0.0f &&
         std::abs(centre.z) <= 0.5f * m_config.depth * d();
}

bool ReposeScupper::inReservoir(const Vec3& centre) const {
  return centre.x < 0.0f && centre.x >= -kWall * d() - m_config.reservoirWidth * d() &&
         centre.y >= m_config.ledge * d() && std::abs(centre.z) <= 0.5f * m_config.depth * d();
}

bool ReposeScupper::contains(const Vec3& centre) const {
  return inSump(centre) || inReservoir(centre);
}

analysis::HeapAngle ReposeScupper::heapAngle(std::span<const BodyState> bodies) const {
  const float zMax = (0.5f * m_config.depth - m_config.wallMargin) * d();
  std::vector<Vec3> centres;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    if (inSump(body.position) && std::abs(body.position.z) <= zMax) {
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

ReposeScupper::GranuleCounts ReposeScupper::countGranules(std::span<const BodyState> bodies) const {
  GranuleCounts counts;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    ++counts.alive;
    counts.sump += inSump(body.position) ? 1 : 0;
    counts.reservoir += inReservoir(body.position) ? 1 : 0;
  }
  return counts;
}

std::vector<SceneMetric> ReposeScupper::metrics(std::span<const BodyState> bodies) const {
  const GranuleCounts counts = countGranules(bodies);
  std::vector<SceneMetric> result{
      {"granules_in_reservoir", static_cast<double>(counts.reservoir)},
      {"granules_in_sump", static_cast<double>(counts.sump)},
      {"granules_lost",
       static_cast<double>(m_config.granules - std::min(m_config.granules, counts.alive))},
      {"release_time_s", releasedAt()},
      {"end_time_s", m_endTime},
      {"settled", m_course.done() && m_course.calm() ? 1.0 : 0.0},
  };
  appendHeapAngleMetrics(
      result, [&] { return heapAngle(bodies); }, d());
  return result;
}

SceneBounds ReposeScupper::bounds() const {
  const float halfDepth = 0.5f * m_config.depth * d();
  return {{-(m_config.reservoirWidth + kWall) * d(), -kSinkDepth * d(), -halfDepth},
          {m_config.sumpLength * d(), wallTop(), halfDepth}};
}

}  // namespace sandphys::scenes
