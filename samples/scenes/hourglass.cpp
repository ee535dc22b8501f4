#include "scenes/hourglass.h"

#include <sandphys/analysis.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "scenes/pour.h"

namespace sandphys::scenes {

namespace {

// kGranuleReach in float, as the scene's geometry is computed.
constexpr float kReach = static_cast<float>(kGranuleReach);
// Largest distance a block's jitter moves a granule centre, d (GranuleBlock::jitter of the
// default spacing along each of three axes).
const float kJitterReach =
    GranuleBlock{}.jitter * kDefaultGranuleSpacing * std::numbers::sqrt3_v<float>;
// Room between a granule of the fill at its farthest jitter and the funnel wall or the gate, d.
constexpr float kClearance = 0.2f;
// Funnel wall above the top of the fill, d.
constexpr float kHeadroom = 6.0f;
// The gate: a slab this thick, reaching this far beyond the outlet's rim under the wall, d.
constexpr float kGateThickness = 2.0f;
constexpr float kGateOverlap = 3.0f;
// Gap between the open gate and the outlet's rim, d.
constexpr float kGateClearance = 3.0f;
// How far the sink extends beyond the outlet's rim and below its top, d: wide and deep enough
// that no granule falls past it.
constexpr float kSinkHalfWidth = 20.0f;
constexpr float kSinkHeight = 50.0f;

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

}  // namespace

float Hourglass::tanHalfAngle() const {
  return std::tan(radians(m_config.halfAngle));
}

float Hourglass::outletY() const {
  return outletRadius() / tanHalfAngle();
}

std::vector<Hourglass::Row> Hourglass::fillRows() const {
  const float s = kDefaultGranuleSpacing;
  const float cosAngle = std::cos(radians(m_config.halfAngle));
  const float tanAngle = tanHalfAngle();
  const float outletRadius = 0.5f * m_config.outlet;
  // A centre this far from the wall (measured normal to it) or from the gate keeps the granule
  // clear of both at any orientation and jitter.
  const float gap = kReach + kJitterReach + kClearance;
  std::vector<Row> rows;
  std::uint32_t left = m_config.granules;
  for (std::uint32_t layer = 0; left > 0; ++layer) {
    const float h = gap + static_cast<float>(layer) * kShiftedLayerHeight;
    // Largest distance of a centre from the axis at height h (all in d).
    const float rho = outletRadius + h * tanAngle - gap / cosAngle;
    if (rho < 0.0f) continue;  // the cone is still too narrow here; halfAngle > 0 ends this
    const float offset = (layer % 2 == 1) ? 0.5f : 0.0f;
    const auto firstRow = static_cast<std::int64_t>(std::ceil(-rho / s - offset));
    const auto lastRow = static_cast<std::int64_t>(std::floor(rho / s - offset));
    for (std::int64_t j = firstRow; j <= lastRow && left > 0; ++j) {
      const float z = (static_cast<float>(j) + offset) * s;
      const float halfRow = std::sqrt(std::max(rho * rho - z * z, 0.0f));
      const auto first = static_cast<std::int64_t>(std::ceil(-halfRow / s - offset));
      const auto last = static_cast<std::int64_t>(std::floor(halfRow / s - offset));
      if (last < first) continue;
      const auto count = static_cast<std::uint32_t>(std::min<std::int64_t>(last - first + 1, left));
      const float x =
          (static_cast<float>(first) + 0.5f * static_cast<float>(count - 1) + offset) * s;
      rows.push_back({{x * d(), outletY() + h * d(), z * d()}, count});
      left -= count;
    }
  }
  return rows;
}

std::vector<BodyState> Hourglass::keptPacking() const {
  // A granule's particles reach kReach below its centre: those lower would start in the gate.
  const float lowest = outletY() + kReach * d();
  std::vector<BodyState> kept;
  for (const BodyState& body : m_packing) {
    if (body.alive && body.granule && body.position.y >= lowest) kept.push_back(body);
  }
  return kept;
}

float Hourglass::fillTop() const {
  if (m_packing.empty()) return fillRows().back().center.y;
  float top = outletY();
  for (const BodyState& body : keptPacking()) top = std::max(top, body.position.y);
  return top;
}

float Hourglass::funnelTop() const {
  return fillTop() + (kReach + kHeadroom) * d();
}

Box Hourglass::gate(bool open) const {
  const float half = outletRadius() + kGateOverlap * d();
  const float x = open ? half + outletRadius() + kGateClearance * d() : 0.0f;
  return Box{.center = {x, outletY() - 0.5f * kGateThickness * d(), 0.0f},
             .halfExtents = {half, 0.5f * kGateThickness * d(), half},
             .inside = false,
             .material = {.friction = m_config.wallFriction, .restitution = m_config.restitution}};
}

WorldSettings Hourglass::worldSettings() const {
  const std::uint64_t granules = m_packing.empty() ? m_config.granules : keptPacking().size();
  if (granules == 0 || 4 * granules > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("hourglass: granules = " + std::to_string(granules) +
                          (m_packing.empty() ? "" : " (of the packing, above the outlet)") +
                          " must be in [1, 1073741823] (a World indexes 4 particles each)");
  }
  if (!(m_config.halfAngle > 0.0f && m_config.halfAngle <= 80.0f)) {
    throw InvalidArgument("hourglass: half-angle = " + std::to_string(m_config.halfAngle) +
                          " degrees must be in (0, 80]");
  }
  if (!(m_config.steadyFrom >= 0.0f && m_config.steadyFrom < m_config.steadyTo &&
        m_config.steadyTo <= 1.0f)) {
    throw InvalidArgument("hourglass: steady-from = " + std::to_string(m_config.steadyFrom) +
                          " and steady-to = " + std::to_string(m_config.steadyTo) +
                          " must satisfy 0 <= steady-from < steady-to <= 1");
  }
  WorldSettings settings;
  settings.particleDiameter = d();
  settings.material.friction = m_config.friction;
  settings.material.restitution = m_config.restitution;
  settings.maxBodies = static_cast<std::uint32_t>(granules);
  settings.maxParticles = static_cast<std::uint32_t>(4 * granules);
  // The count of granules remaining comes from every step's stats.
  settings.statsEachFrame = true;
  // The speed guard is that of a free fall from an arch of the outlet's size over the outlet to
  // the sink, or of the fill's collapse if that is faster: grains inside the funnel move slower.
  float fall = (0.5f * m_config.outlet + kSinkDepth) * d();
  if (m_packing.empty()) {
    // Before the release the fill's lattice collapses: its top falls about a third of its
    // height, and some grains fall further: the guard takes a fall of half its height.
    const std::vector<Row> rows = fillRows();
    fall = std::max(fall, 0.5f * (rows.back().center.y - rows.front().center.y));
  }
  settings.maxSpeed = pourGuardSpeed(0.0f, fall, gravityMagnitude(settings));
  settings.stepsPerContact = m_config.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, m_config.youngsModulus);
  return settings;
}

void Hourglass::build(World& world) {
  m_released = false;
  m_finished = false;
  m_releasedAt = -1.0;
  m_lastDrainTime = 0.0;
  m_granulesAtRelease = 0;
  m_lastRemaining = 0;
  m_guardsAtRelease = {};
  m_guards = {};
  m_remaining.clear();
  m_packingAtRelease.clear();
  m_funnelTop = funnelTop();
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;

  world.addCollider(
      Funnel{.outletCenter = {0.0f, outletY(), 0.0f},
             .outletRadius = outletRadius(),
             .halfAngle = radians(m_config.halfAngle),
             .height = m_funnelTop - outletY(),
             .material = {.friction = m_config.wallFriction, .restitution = m_config.restitution}});
  m_gate = world.addCollider(gate(false));
  const float sinkHalf = outletRadius() + kSinkHalfWidth * d();
  world.addSink(Sink{.min = {-sinkHalf, outletY() - (kSinkDepth + kSinkHeight) * d(), -sinkHalf},
                     .max = {sinkHalf, outletY() - kSinkDepth * d(), sinkHalf}});

  if (!m_packing.empty()) {
    addPacking(world);
    return;
  }
  const std::vector<Row> rows = fillRows();
  const float spacing = kDefaultGranuleSpacing * d();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    world.addGranules(GranuleBlock{.center = rows[i].center,
                                   .countX = rows[i].count,
                                   .countY = 1,
                                   .countZ = 1,
                                   .spacing = spacing,
                                   .seed = m_config.seed * 1000003u + i});
  }
}

void Hourglass::addPacking(World& world) const {
  std::vector<BodyDesc> poses;
  for (const BodyState& granule : keptPacking())
    poses.push_back({.position = granule.position, .orientation = granule.orientation});
  world.addGranules(poses);
}

void Hourglass::update(World& world, const StepReport& report, double simTime) {
  if (m_finished) return;
  if (!m_released) {
    const bool calm =
        granulesCalm(report, report.stats.granulesAlive, m_granuleMass, m_config.settleSpeed);
    if (!releaseDue(calm, simTime, m_config.releaseTime, m_config.maxSettleSeconds)) return;
    // The fill as it settled, for startFrom of later runs: one read-back per run.
    for (const BodyState& body : world.readBodies()) {
      if (body.alive && body.granule) m_packingAtRelease.push_back(body);
    }
    world.setCollider(m_gate, gate(true));
    m_released = true;
    m_releasedAt = simTime;
    m_granulesAtRelease = report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
    m_guardsAtRelease = {report.stats.penetrationClamps, report.stats.velocityClamps};
    m_guards = m_guardsAtRelease;
    m_lastRemaining = m_granulesAtRelease;
    m_lastDrainTime = simTime;
    m_remaining.push_back({0.0, static_cast<double>(m_granulesAtRelease)});
    return;
  }
  // settings() turns the stats on; a frame that ran no substep adds no new time.
  if (!report.hasStats || simTime - m_releasedAt <= m_remaining.back()[0]) return;
  const std::uint32_t left = report.stats.granulesAlive;
  m_guards = {report.stats.penetrationClamps, report.stats.velocityClamps};
  m_remaining.push_back({simTime - m_releasedAt, static_cast<double>(left)});
  if (left < m_lastRemaining) {
    m_lastRemaining = left;
    m_lastDrainTime = simTime;
  }
  if (left == 0 || simTime - m_lastDrainTime >= m_config.stallSeconds) m_finished = true;
}

Hourglass::FlowFit Hourglass::flowFit() const {
  FlowFit fit;
  if (m_granulesAtRelease == 0 || m_remaining.empty()) return fit;
  const double n0 = m_granulesAtRelease;
  const double startLevel = n0 * (1.0 - m_config.steadyFrom);
  const double endLevel = n0 * (1.0 - m_config.steadyTo);
  std::size_t first = 0;
  while (first < m_remaining.size() && m_remaining[first][1] > startLevel) ++first;
  if (first == m_remaining.size()) return fit;  // never drained that far: no steady part
  std::size_t last = first;
  while (last + 1 < m_remaining.size() && m_remaining[last][1] > endLevel) ++last;
  fit.start = m_remaining[first][0];
  fit.end = m_remaining[last][0];
  fit.samples = last - first + 1;
  if (fit.samples < 3) return fit;
  std::vector<double> t;
  std::vector<double> n;
  for (std::size_t i = first; i <= last; ++i) {
    t.push_back(m_remaining[i][0]);
    n.push_back(m_remaining[i][1]);
  }
  const analysis::LineFit line = analysis::fitLine(t, n);
  fit.rate = -line.slope;
  fit.rSquared = line.rSquared;
  return fit;
}

std::string Hourglass::status() const {
  if (!m_released) return "settling";
  if (m_lastRemaining == 0) return "empty";
  const std::string left = std::to_string(m_lastRemaining) + " left";
  return m_finished ? "stopped: " + left : "draining: " + left;
}

bool Hourglass::contains(const Vec3& centre) const {
  const float radial = std::hypot(centre.x, centre.z);
  if (centre.y < outletY()) {
    // Through the outlet, on the way to the sink (a granule's centre enters it kSinkDepth below).
    return centre.y >= outletY() - (kSinkDepth + 1.0f) * d() &&
           radial <= outletRadius() + kGateOverlap * d();
  }
  // m_funnelTop: contains() is asked for every granule at the end of a run.
  return centre.y <= m_funnelTop && radial <= centre.y * tanHalfAngle() + 0.25f * d();
}

std::vector<SceneMetric> Hourglass::metrics(std::span<const BodyState> bodies) const {
  std::size_t inFunnel = 0;
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && body.position.y > outletY()) ++inFunnel;
  }
  const FlowFit fit = flowFit();
  // The fill's height above the outlet and its width there when the gate opened, for the
  // paper's conditions of a steady flow (height >= 2.5 W, W > D + 30 d). The 99th percentile of
  // the centres plus a granule's reach: a few granules resting high do not count.
  double fillHeight = 0.0;
  double fillWidth = 0.0;
  if (!m_packingAtRelease.empty()) {
    std::vector<float> heights;
    for (const BodyState& body : m_packingAtRelease) heights.push_back(body.position.y);
    fillHeight = percentile(heights, 0.99) + kReach * d() - outletY();
    fillWidth = 2.0 * (outletRadius() + fillHeight * tanHalfAngle());
  }
  return {
      {"granules_at_release", static_cast<double>(m_granulesAtRelease)},
      {"fill_height_d", fillHeight / d()},
      {"fill_width_d", fillWidth / d()},
      {"granules_in_funnel", static_cast<double>(inFunnel)},
      {"released", m_released ? 1.0 : 0.0},
      {"release_time_s", m_releasedAt},
      {"outlet_d", m_config.outlet},
      {"half_angle_deg", m_config.halfAngle},
      {"friction", m_config.friction},
      {"flow_rate_per_s", fit.rate},
      {"flow_rate_r2", fit.rSquared},
      // The settling lattice collapses hard (its top falls a third of its height); what counts
      // for the flow is whether the guards fire while it drains.
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

std::vector<SceneParameter> Hourglass::parameters() {
  return {
      {"granules", "granules in the funnel", &m_config.granules, 1, 16777216},
      {"outlet", "outlet diameter D, d (0 closes the funnel)", &m_config.outlet, 0.0, 1000.0},
      {"half-angle", "angle of the funnel wall from the vertical, degrees", &m_config.halfAngle,
       1.0, 80.0},
      {"friction", "friction coefficient of grain-grain contacts", &m_config.friction, 0.0, 10.0},
      {"wall-friction", "friction coefficient of the funnel wall and the gate",
       &m_config.wallFriction, 0.0, 10.0},
      {"youngs-modulus", kYoungsModulusHelp, &m_config.youngsModulus, 0.0, 1e12},
      {"restitution", "coefficient of restitution of impacts", &m_config.restitution, 0.01, 1.0},
      {"release-time", "earliest time the outlet opens, s", &m_config.releaseTime, 0.0, 1e9},
      {"settle-speed", "the fill has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-settle-seconds", "longest wait for the fill to settle past release-time, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"steady-from", "the steady flow starts when this fraction has left", &m_config.steadyFrom,
       0.0, 0.99},
      {"steady-to", "the steady flow ends when this fraction has left", &m_config.steadyTo, 0.01,
       1.0},
      {"stall-seconds", "finished when no granule has left for this long, s",
       &m_config.stallSeconds, 0.01, 1e6},
      {"steps-per-contact", "substeps per Hertz contact time at the speed guard",
       &m_config.stepsPerContact, kMinStepsPerContact, 1e3},
      {"seed", "random seed of the fill", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds Hourglass::bounds() const {
  const float top = funnelTop();
  const float radius = top * tanHalfAngle();
  const float bottom = outletY() - (kSinkDepth + kGateThickness) * d();
  return {{-radius, bottom, -radius}, {radius, top, radius}};
}

}  // namespace sandphys::scenes
