#include "scenes/hourglass.h"

#include <sandphys/analysis.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <string>

#include "scenes/kit/checks.h"
#include "scenes/kit/gated_fill.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kReach;
// In d. A fill granule's centre stays kReach + kJitterReach + kFillClearance from the wall and
// the gate (the jitter along three axes: the wall is a cone); the wall stands kHeadroom above it.
const float kJitterReach = kit::kJitter * std::numbers::sqrt3_v<float>;
constexpr float kHeadroom = 6.0f;
// The gate's slab reaches kGateOverlap beyond the outlet's rim, and kGateClearance clear of the
// rim when open. The sink's top lies kSinkDepth below the outlet, where a granule has wholly
// passed it.
constexpr float kGateThickness = 2.0f;
constexpr float kGateOverlap = 3.0f;
constexpr float kGateClearance = 3.0f;
constexpr float kSinkDepth = 2.0f;
constexpr float kSinkHalfWidth = 20.0f;
constexpr float kSinkHeight = 50.0f;

using C = HourglassConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"granules", &C::granules, "", 1, 16777216, "granules in the funnel"},
    {"outlet", &C::outlet, "d", 0.0, 1000.0, "outlet diameter D (0 closes the funnel)"},
    {"half-angle", &C::halfAngle, "deg", 1.0, 80.0, "angle of the funnel wall from the vertical"},
    {"friction", &C::friction, "", 0.0, 10.0, "friction coefficient of grain-grain contacts"},
    {"wall-friction", &C::wallFriction, "", 0.0, 10.0,
     "friction coefficient of the funnel wall and the gate"},
    {"release-time", &C::releaseTime, "s", 0.0, 1e9, "earliest time the outlet opens"},
    {"steady-from", &C::steadyFrom, "", 0.0, 0.99,
     "the steady flow starts when this fraction has left"},
    {"steady-to", &C::steadyTo, "", 0.01, 1.0, "the steady flow ends when this fraction has left"},
    {"stall-seconds", &C::stallSeconds, "s", 0.01, 1e6,
     "finished when no granule has left for this long"},
    {"steps-per-contact", &C::stepsPerContact, "", kMinStepsPerContact, 1e3,
     "substeps per Hertz contact time at the speed guard"},
});

// The first and the last lattice slot i with |(i + offset) spacing| <= half, in d.
std::array<std::int64_t, 2> slots(float half, float offset) {
  const float s = kDefaultGranuleSpacing;
  return {static_cast<std::int64_t>(std::ceil(-half / s - offset)),
          static_cast<std::int64_t>(std::floor(half / s - offset))};
}

}  // namespace

std::span<const kit::Param<C>> Hourglass::table() const {
  return kTable;
}

std::vector<GranuleBlock> Hourglass::fillRows() const {
  const float s = kDefaultGranuleSpacing;
  const float cosAngle = std::cos(halfAngle());
  const float tanAngle = tanHalfAngle();
  const float gap = kReach + kJitterReach + kit::kFillClearance;
  kit::FillBlocks fill(m_config.granules, m_config.seed);
  for (std::uint32_t layer = 0; fill.left() > 0; ++layer) {
    const float h = gap + static_cast<float>(layer) * kit::kShiftedLayerHeight;
    // Largest distance of a centre from the axis at height h above the outlet.
    const float rho = 0.5f * m_config.outlet + h * tanAngle - gap / cosAngle;
    if (rho < 0.0f) continue;  // still too narrow here; halfAngle > 0 ends this
    const float offset = (layer % 2 == 1) ? 0.5f : 0.0f;
    const auto [firstRow, lastRow] = slots(rho, offset);
    for (std::int64_t j = firstRow; j <= lastRow && fill.left() > 0; ++j) {
      const float z = (static_cast<float>(j) + offset) * s;
      const auto [first, last] = slots(std::sqrt(std::max(rho * rho - z * z, 0.0f)), offset);
      if (last < first) continue;
      const auto count =
          static_cast<std::uint32_t>(std::min<std::int64_t>(last - first + 1, fill.left()));
      const float x =
          (static_cast<float>(first) + 0.5f * static_cast<float>(count - 1) + offset) * s;
      fill.add({.center = {x * d(), outletY() + h * d(), z * d()},
                .countX = count,
                .countY = 1,
                .countZ = 1,
                .spacing = s * d()});
    }
  }
  return fill.blocks();
}

std::vector<BodyState> Hourglass::keptPacking() const {
  // A granule reaches kReach below its centre: one lower would start in the gate.
  const float lowest = outletY() + kReach * d();
  std::vector<BodyState> kept;
  for (const BodyState& body : kit::granulesIn(m_packing)) {
    if (body.position.y >= lowest) kept.push_back(body);
  }
  return kept;
}

float Hourglass::funnelTop() const {
  float top = m_packing.empty() ? fillRows().back().center.y : outletY();
  for (const BodyState& body : keptPacking()) top = std::max(top, body.position.y);
  return top + (kReach + kHeadroom) * d();
}

Box Hourglass::gate(bool open) const {
  const float half = outletRadius() + kGateOverlap * d();
  const float x = open ? half + outletRadius() + kGateClearance * d() : 0.0f;
  return Box{.center = {x, outletY() - 0.5f * kGateThickness * d(), 0.0f},
             .halfExtents = {half, 0.5f * kGateThickness * d(), half},
             .inside = false,
             .material = kit::wallMaterial(m_config)};
}

WorldSettings Hourglass::worldSettings() const {
  const Config& c = m_config;
  kit::require(c.steadyFrom < c.steadyTo, name(), "steady-from ", c.steadyFrom,
               " must be below steady-to ", c.steadyTo);
  const std::uint64_t granules = m_packing.empty() ? c.granules : keptPacking().size();
  kit::require(granules > 0, name(), "no granule of the packing lies above the outlet plane (",
               c.outlet, " d wide)");
  // The guard: a fall from an arch over the outlet to the sink, or from half the lattice's
  // height as it collapses while it settles.
  float fall = (0.5f * c.outlet + kSinkDepth) * d();
  if (m_packing.empty()) {
    const std::vector<GranuleBlock> rows = fillRows();
    fall = std::max(fall, 0.5f * (rows.back().center.y - rows.front().center.y));
  }
  return kit::worldSettings(name(), d(), kit::gatedFillRule(c, granules, fall));
}

void Hourglass::build(World& world) {
  m_course = kit::gateCourse(m_config, world.settings());
  m_remaining.clear();
  m_packingAtRelease.clear();
  m_lastDrainTime = 0.0;
  m_granulesAtRelease = 0;
  m_guardsAtRelease = m_guards = {};
  m_funnelTop = funnelTop();
  world.addCollider(Funnel{.outletCenter = {0.0f, outletY(), 0.0f},
                           .outletRadius = outletRadius(),
                           .halfAngle = halfAngle(),
                           .height = m_funnelTop - outletY(),
                           .material = kit::wallMaterial(m_config)});
  m_gate = world.addCollider(gate(false));
  const float sinkHalf = outletRadius() + kSinkHalfWidth * d();
  world.addSink(Sink{.min = {-sinkHalf, outletY() - (kSinkDepth + kSinkHeight) * d(), -sinkHalf},
                     .max = {sinkHalf, outletY() - kSinkDepth * d(), sinkHalf}});
  if (m_packing.empty()) {
    for (const GranuleBlock& row : fillRows()) world.addGranules(row);
    return;
  }
  std::vector<BodyDesc> poses;
  for (const BodyState& granule : keptPacking()) {
    poses.push_back({.position = granule.position, .orientation = granule.orientation});
  }
  world.addGranules(poses);
}

void Hourglass::update(World& world, const StepReport& report, double simTime) {
  if (finished()) return;
  if (m_course.update(report, simTime)) {
    // The fill as it settled, for startFrom of later runs: one read-back per run.
    std::ranges::copy(kit::granulesIn(world.readBodies()), std::back_inserter(m_packingAtRelease));
    world.setCollider(m_gate, gate(true));
    m_granulesAtRelease = report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
    m_guardsAtRelease = m_guards = {report.stats.penetrationClamps, report.stats.velocityClamps};
    m_lastDrainTime = simTime;
    m_remaining.push_back({0.0, static_cast<double>(m_granulesAtRelease)});
    return;
  }
  // A frame that ran no substep adds no new time.
  if (!m_course.acting() || !report.hasStats || simTime - releasedAt() <= m_remaining.back()[0]) {
    return;
  }
  const std::uint32_t left = report.stats.granulesAlive;
  m_guards = {report.stats.penetrationClamps, report.stats.velocityClamps};
  // Granules only ever leave: a count below the last sample's is a new low.
  if (left < m_remaining.back()[1]) m_lastDrainTime = simTime;
  m_remaining.push_back({simTime - releasedAt(), static_cast<double>(left)});
  if (left == 0 || simTime - m_lastDrainTime >= m_config.stallSeconds) m_course.endAct(simTime);
}

Hourglass::FlowFit Hourglass::flowFit() const {
  FlowFit fit;
  const auto& r = m_remaining;
  // The first sample at or below `fraction` of the fill left, from `from` on.
  const auto down = [&](auto from, float fraction) {
    const double level = m_granulesAtRelease * (1.0 - fraction);
    return std::find_if(from, r.end(), [&](const auto& sample) { return sample[1] <= level; });
  };
  const auto first = down(r.begin(), m_config.steadyFrom);
  if (m_granulesAtRelease == 0 || first == r.end()) return fit;  // no steady part
  const auto last = std::min(down(first, m_config.steadyTo), r.end() - 1);
  fit.start = (*first)[0];
  fit.end = (*last)[0];
  fit.samples = static_cast<std::size_t>(last - first + 1);
  if (fit.samples < 3) return fit;
  std::vector<double> t;
  std::vector<double> n;
  for (auto sample = first; sample <= last; ++sample) {
    t.push_back((*sample)[0]);
    n.push_back((*sample)[1]);
  }
  const analysis::LineFit line = analysis::fitLine(t, n);
  fit.rate = -line.slope;
  fit.rSquared = line.rSquared;
  return fit;
}

std::string Hourglass::status() const {
  if (releasedAt() < 0.0) return "settling";
  const auto remaining = static_cast<std::uint32_t>(m_remaining.back()[1]);
  if (remaining == 0) return "empty";
  const std::string left = std::to_string(remaining) + " left";
  return finished() ? "stopped: " + left : "draining: " + left;
}

bool Hourglass::contains(const Vec3& centre) const {
  const float radial = std::hypot(centre.x, centre.z);
  if (centre.y < outletY()) {
    // Through the outlet, on the way to the sink.
    return centre.y >= outletY() - (kSinkDepth + 1.0f) * d() &&
           radial <= outletRadius() + kGateOverlap * d();
  }
  return centre.y <= m_funnelTop && radial <= centre.y * tanHalfAngle() + 0.25f * d();
}

std::vector<SceneMetric> Hourglass::metrics(std::span<const BodyState> bodies) const {
  std::size_t inFunnel = 0;
  for (const BodyState& body : kit::granulesIn(bodies)) inFunnel += body.position.y > outletY();
  const FlowFit fit = flowFit();
  // The fill's height above the outlet and its width there at the release, for the paper's
  // conditions of a steady flow (height >= 2.5 W, W > D + 30 d).
  double fillHeight = 0.0;
  double fillWidth = 0.0;
  if (!m_packingAtRelease.empty()) {
    fillHeight = kit::pileSurface(
                     m_packingAtRelease, [](const Vec3&) { return true; }, kReach * d()) -
                 outletY();
    fillWidth = 2.0 * (outletRadius() + fillHeight * tanHalfAngle());
  }
  return {
      {"granules_at_release", static_cast<double>(m_granulesAtRelease)},
      {"fill_height_d", fillHeight / d()},
      {"fill_width_d", fillWidth / d()},
      {"granules_in_funnel", static_cast<double>(inFunnel)},
      {"released", releasedAt() >= 0.0 ? 1.0 : 0.0},
      {"release_time_s", releasedAt()},
      {"flow_rate_per_s", fit.rate},
      {"flow_rate_r2", fit.rSquared},
      // The settling lattice collapses hard; what counts is the guards while it drains.
      {"penetration_clamps_draining", static_cast<double>(m_guards[0] - m_guardsAtRelease[0])},
      {"velocity_clamps_draining", static_cast<double>(m_guards[1] - m_guardsAtRelease[1])},
  };
}

std::vector<SceneSeries> Hourglass::series() const {
  const FlowFit fit = flowFit();
  return {{"remaining",
           m_remaining,
           {
               {"flow_rate", fit.rate},
               {"flow_rate_r2", fit.rSquared},
               {"flow_steady_start_s", fit.start},
               {"flow_steady_end_s", fit.end},
               {"flow_steady_samples", static_cast<double>(fit.samples)},
           }}};
}

SceneBounds Hourglass::bounds() const {
  const float top = funnelTop();
  const float radius = top * tanHalfAngle();
  const float bottom = outletY() - (kSinkDepth + kGateThickness) * d();
  return {{-radius, bottom, -radius}, {radius, top, radius}};
}

}  // namespace sandphys::scenes
