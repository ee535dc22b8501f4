#include "scenes/bulldozer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

namespace sandphys::scenes {

namespace {

// kGranuleReach in float, as the scene's geometry is computed.
constexpr float kReach = static_cast<float>(kGranuleReach);
// Largest jitter of a berm granule per axis, d (GranuleBlock::jitter of the default spacing).
const float kJitter = GranuleBlock{}.jitter * kDefaultGranuleSpacing;
// Gap between the blade's particles and the floor, d: the blade must not touch the floor (its
// force would count as the sand's), and a grain (at least d across) must not pass beneath it.
constexpr float kFloorClearance = 0.25f;
// Thickness of the blade's box between the centres of its front and back particles, d: the two
// sheets touch, so the blade is a solid wall two diameters thick.
constexpr float kBladeThickness = 1.0f;
// Room around the scene's contents in the bounds, d.
constexpr float kMargin = 2.0f;
// How far beyond the bounds a grain may roll on the floor before it counts as lost, d.
constexpr float kRoam = 20.0f;
// Fastest blade a World of this scene accepts, m/s: grains thrown ahead of a faster one need a
// speed guard, and so a time step, that would make the scene crawl.
constexpr float kMaxBladeSpeed = 5.0f;
// The speed guard is this multiple of the blade's speed (grains thrown off its face move faster
// than it), and never below kMinGuardSpeed, which covers the berm's short settling drop.
constexpr float kGuardPerBladeSpeed = 4.0f;
constexpr float kMinGuardSpeed = 2.0f;
// Substeps per Hertz contact time at the guard speed (the minimum is 8), as slope-avalanche.
constexpr float kStepsPerContact = 10.0f;
// After the push the sand needs a moment to show whether it keeps moving, s.
constexpr double kMinRestSeconds = 0.1;

void requireAtLeast(std::string_view field, float value, float limit) {
  if (!(value >= limit)) {
    throw InvalidArgument("bulldozer: Config." + std::string(field) + " = " +
                          std::to_string(value) + " must be >= " + std::to_string(limit));
  }
}

}  // namespace

std::uint32_t Bulldozer::bermGranules() const {
  return m_config.berm[0] * m_config.berm[1] * m_config.berm[2];
}

float Bulldozer::spacing() const {
  return kDefaultGranuleSpacing * d();
}

float Bulldozer::bermLift() const {
  return (kReach + kJitter + 0.15f) * d();
}

Vec3 Bulldozer::bladeHalfExtents() const {
  const float halfAcross = 0.5f * static_cast<float>(m_config.berm[2] - 1) * spacing();
  // Particle centres lie on the box, so its faces are half a diameter inside the blade's.
  return {0.5f * kBladeThickness * d(), 0.5f * (m_config.bladeHeight - 1.0f) * d(),
          halfAcross + m_config.bladeOverhang * d()};
}

float Bulldozer::bladeFaceStart() const {
  const float halfAlong = 0.5f * static_cast<float>(m_config.berm[0] - 1) * spacing();
  return -halfAlong - (kReach + kJitter + m_config.gap) * d();
}

Vec3 Bulldozer::bladeStart() const {
  const Vec3 half = bladeHalfExtents();
  return {bladeFaceStart() - 0.5f * d() - half.x, (kFloorClearance + 0.5f) * d() + half.y, 0.0f};
}

float Bulldozer::bladeTravel() const {
  return m_config.bladeSpeed > 0.0f ? m_config.pushDistance * d() : 0.0f;
}

SampledMesh Bulldozer::bladeShape() const {
  const Vec3 half = bladeHalfExtents();
  TriangleMesh box = boxMesh({-half.x, -half.y, -half.z}, half);
  box.source = "bulldozer blade";
  return sampleMesh(box, d());
}

WorldSettings Bulldozer::worldSettings() const {
  requireAtLeast("particleDiameter", m_config.particleDiameter, 1e-6f);
  requireAtLeast("bladeSpeed", m_config.bladeSpeed, 0.0f);
  if (!(m_config.bladeSpeed <= kMaxBladeSpeed)) {
    throw InvalidArgument("bulldozer: Config.bladeSpeed = " + std::to_string(m_config.bladeSpeed) +
                          " m/s must be <= " + std::to_string(kMaxBladeSpeed));
  }
  requireAtLeast("pushDistance", m_config.pushDistance, 0.0f);
  requireAtLeast("pushStart", m_config.pushStart, 0.0f);
  requireAtLeast("gap", m_config.gap, 0.0f);
  // Below two diameters the blade's box would be flat and its sampling degenerate.
  requireAtLeast("bladeHeight", m_config.bladeHeight, 2.0f);
  requireAtLeast("bladeOverhang", m_config.bladeOverhang, 0.0f);
  requireAtLeast("floorFriction", m_config.floorFriction, 0.0f);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (m_config.berm[axis] == 0) {
      throw InvalidArgument("bulldozer: Config.berm[" + std::to_string(axis) +
                            "] = 0 must be >= 1");
    }
  }
  WorldSettings settings;
  settings.particleDiameter = d();
  const std::uint64_t granules =
      static_cast<std::uint64_t>(m_config.berm[0]) * m_config.berm[1] * m_config.berm[2];
  const std::uint64_t bladeParticles = bladeShape().centres.size();
  if (4 * granules + bladeParticles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument(
        "bulldozer: berm of " + std::to_string(granules) + " granules and a blade of " +
        std::to_string(bladeParticles) + " particles are more than a World can index (" +
        std::to_string(std::numeric_limits<std::uint32_t>::max()) + " particles)");
  }
  settings.maxBodies = static_cast<std::uint32_t>(granules + 1);
  settings.maxParticles = static_cast<std::uint32_t>(4 * granules + bladeParticles);
  settings.maxSpeed = std::max(kMinGuardSpeed, kGuardPerBladeSpeed * m_config.bladeSpeed);
  settings.stepsPerContact = kStepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings);
  return settings;
}

void Bulldozer::build(World& world) {
  m_phase = Phase::Waiting;
  for (BladeLoad& load : m_loads) load = {};
  m_drag.clear();
  m_atPushStart.clear();
  m_atPushEnd.clear();
  m_stoppedAt = -1.0;
  m_finished = false;
  m_stepsRun = 0;
  m_granuleMass = tetrahedronTemplate(d(), world.settings().material.density).mass;
  m_timeStep = world.timeStep();

  world.addCollider(Plane{.normal = {0.0f, 1.0f, 0.0f},
                          .offset = 0.0f,
                          .material = {.friction = m_config.floorFriction}});
  const float blockHeight = static_cast<float>(m_config.berm[1] - 1) * spacing();
  world.addGranules(GranuleBlock{.center = {0.0f, bermLift() + 0.5f * blockHeight, 0.0f},
                                 .countX = m_config.berm[0],
                                 .countY = m_config.berm[1],
                                 .countZ = m_config.berm[2],
                                 .spacing = spacing(),
                                 .seed = m_config.seed});
  m_blade = world.addBody(bladeShape().shape,
                          BodyDesc{.position = bladeStart(), .motion = Motion::Kinematic});

  // The World runs the push in whole substeps (see the class comment); a blade that does not
  // move is given a move in place, for the substep where the push would start.
  const float travel = bladeTravel();
  Vec3 end = bladeStart();
  end.x += travel;
  const KinematicMovePlan push = world.moveKinematic(
      m_blade,
      KinematicMove{
          .from = bladeStart(),
          .to = end,
          .startTime = m_config.pushStart,
          .duration = travel > 0.0f ? static_cast<double>(travel) / m_config.bladeSpeed : 0.0});
  m_pushStartStep = push.startStep;
  m_pushSteps = travel > 0.0f ? push.endStep - push.startStep : 0;

  // Until the push starts, the metrics measure from the lattice (a sync point at setup only).
  m_reference = world.readBodies();
  m_bermFront = -std::numeric_limits<float>::infinity();
  for (const BodyState& body : m_reference) {
    if (body.granule) m_bermFront = std::max(m_bermFront, body.position.x);
  }
}

void Bulldozer::readLoad(World& world) {
  for (const BodyForce& force : world.takeBodyForces()) {
    if (force.body != m_blade || force.substeps == 0) continue;
    BladeLoad& load = m_loads[static_cast<int>(m_phase)];
    load.impulse[0] += static_cast<double>(force.force.x) * m_timeStep;
    load.impulse[1] += static_cast<double>(force.force.y) * m_timeStep;
    load.impulse[2] += static_cast<double>(force.force.z) * m_timeStep;
    load.substeps += force.substeps;
    const Vec3 mean = force.meanForce();
    // 0 - x rather than -x: no "-0" drag in the metrics of a blade that never touched sand.
    m_drag.push_back({world.simulatedTime(), 0.0f - mean.x, mean.y, m_phase});
  }
}

std::uint64_t Bulldozer::phaseEnd() const {
  switch (m_phase) {
    case Phase::Waiting:
      return m_pushStartStep;
    case Phase::Pushing:
      return m_pushStartStep + m_pushSteps;
    case Phase::Stopped:
      break;
  }
  return std::numeric_limits<std::uint64_t>::max();
}

void Bulldozer::endPhases(World& world) {
  const std::uint64_t now = world.stepCount();
  // A phase ends: its force is read before the next one's substeps add to it.
  if (m_phase == Phase::Waiting && now >= phaseEnd()) {
    readLoad(world);
    m_atPushStart = world.readBodies();
    m_reference = m_atPushStart;
    m_bermFront = -std::numeric_limits<float>::infinity();
    for (const BodyState& body : m_reference) {
      if (body.granule) m_bermFront = std::max(m_bermFront, body.position.x);
    }
    m_phase = Phase::Pushing;
  }
  if (m_phase == Phase::Pushing && now >= phaseEnd()) {
    readLoad(world);
    m_atPushEnd = world.readBodies();
    m_stoppedAt = world.simulatedTime();
    m_phase = Phase::Stopped;
  }
}

StepReport Bulldozer::step(World& world, float frameDt) {
  if (!m_blade.isValid()) return world.step(frameDt);
  endPhases(world);
  // The World stops where the current phase ends and holds the rest of the frame for the next
  // phase.
  StepReport report = world.step(frameDt, phaseEnd());
  while (report.substepsHeld > 0) {
    endPhases(world);
    report.append(world.step(0.0f, phaseEnd()));
  }
  readLoad(world);
  m_stepsRun = world.stepCount();
  return report;
}

void Bulldozer::update(World& /*world*/, const StepReport& report, double simTime) {
  if (m_finished || m_phase != Phase::Stopped) return;
  const bool calm = granulesCalm(report, bermGranules(), m_granuleMass, m_config.settleSpeed);
  const double sinceStop = simTime - m_stoppedAt;
  if (sinceStop < kMinRestSeconds) return;
  if (!calm && sinceStop < m_config.maxSettleSeconds) return;
  m_finished = true;
}

std::string Bulldozer::status() const {
  switch (m_phase) {
    case Phase::Waiting:
      return "settling";
    case Phase::Pushing: {
      char text[96];
      const float drag = m_drag.empty() ? 0.0f : m_drag.back().drag;
      const double done = static_cast<double>(std::min(m_stepsRun - m_pushStartStep, m_pushSteps));
      const double travelled =
          m_pushSteps > 0 ? m_config.pushDistance * done / static_cast<double>(m_pushSteps) : 0.0;
      std::snprintf(text, sizeof text, "pushing %.1f/%.0f d, drag %.2f N", travelled,
                    m_config.pushDistance, drag);
      return text;
    }
    case Phase::Stopped:
      return m_finished ? "stopped, sand at rest" : "stopped";
  }
  return {};
}

bool Bulldozer::contains(const Vec3& centre) const {
  // The floor has no edge: a grain is lost only when it is below the floor or has rolled far
  // beyond the picture's bounds.
  const SceneBounds b = bounds();
  const float roam = kRoam * d();
  return centre.y >= 0.0f && centre.y <= b.max.y && centre.x >= b.min.x - roam &&
         centre.x <= b.max.x + roam && std::abs(centre.z) <= b.max.z + roam;
}

std::vector<SceneMetric> Bulldozer::metrics(std::span<const BodyState> bodies) const {
  std::vector<const BodyState*> before;
  for (const BodyState& body : m_reference) {
    if (!body.granule) continue;
    if (body.index >= before.size()) before.resize(body.index + 1, nullptr);
    before[body.index] = &body;
  }
  double shift = 0.0;
  std::size_t granules = 0;
  std::size_t matched = 0;
  std::size_t ahead = 0;
  float bladeX = bladeStart().x;
  for (const BodyState& body : bodies) {
    if (m_blade.isValid() && body.index == m_blade.index && !body.granule) {
      bladeX = body.position.x;
      continue;
    }
    if (!body.granule || !body.alive) continue;
    ++granules;
    if (body.position.x > m_bermFront) ++ahead;
    if (body.index >= before.size() || !before[body.index]) continue;
    shift += body.position.x - before[body.index]->position.x;
    ++matched;
  }
  if (matched > 0) shift /= static_cast<double>(matched);

  const BladeLoad& push = load(Phase::Pushing);
  const double pushSeconds = static_cast<double>(push.substeps) * m_timeStep;
  float peak = 0.0f;
  for (const DragSample& sample : m_drag) {
    if (sample.phase == Phase::Pushing) peak = std::max(peak, sample.drag);
  }
  const double travel = bladeX - bladeStart().x;
  return {
      {"granules", static_cast<double>(granules)},
      {"blade_travel_m", travel},
      {"blade_travel_d", travel / d()},
      {"push_seconds", pushSeconds},
      // The sand's impulse on the blade against the push over the push, N s, and its mean.
      {"drag_impulse_ns", 0.0 - push.impulse[0]},
      {"drag_mean_n", pushSeconds > 0.0 ? (0.0 - push.impulse[0]) / pushSeconds : 0.0},
      {"drag_peak_n", peak},
      // The last reading: after the push, the sand leaning on the stopped blade.
      {"drag_now_n", m_drag.empty() ? 0.0 : m_drag.back().drag},
      // Since the start of the push (since build before it).
      {"com_shift_m", shift},
      {"com_shift_d", shift / d()},
      {"berm_front_x_m", m_bermFront},
      {"pushed_fraction",
       granules > 0 ? static_cast<double>(ahead) / static_cast<double>(granules) : 0.0},
  };
}

std::vector<SceneBody> Bulldozer::bodies(const World& world) const {
  if (!m_blade.isValid()) return {};
  const BodyState blade = world.readBody(m_blade);
  const Quat& q = blade.orientation;
  // The blade starts upright: the tilt is the angle of its y axis from the world's, whose y
  // component is 1 - 2 (x² + z²).
  const float up = std::clamp(1.0f - 2.0f * (q.x * q.x + q.z * q.z), -1.0f, 1.0f);
  return {{.name = "blade",
           .position = blade.position,
           .orientation = q,
           .speed = std::hypot(blade.velocity.x, blade.velocity.y, blade.velocity.z),
           .tiltDegrees = std::acos(up) * 180.0f / std::numbers::pi_v<float>}};
}

std::vector<SceneParameter> Bulldozer::parameters() {
  return {
      {"berm", "granules of the berm along x (the push), y (layers), z (across)", &m_config.berm, 1,
       1024},
      {"blade-speed", "speed of the blade during the push, m/s (0: it stays put)",
       &m_config.bladeSpeed, 0.0, kMaxBladeSpeed},
      {"push-distance", "distance the blade travels, d", &m_config.pushDistance, 0.0, 1e4},
      {"push-start", "time the push starts (the berm settles until then), s", &m_config.pushStart,
       0.0, 1e6},
      {"gap", "gap between the blade and the berm at the start, d", &m_config.gap, 0.0, 1e3},
      {"blade-height", "height of the blade, d", &m_config.bladeHeight, 2.0, 1e3},
      {"blade-overhang", "how far the blade reaches beyond the berm on each side, d",
       &m_config.bladeOverhang, 0.0, 1e3},
      {"floor-friction", "friction coefficient of the floor", &m_config.floorFriction, 0.0, 10.0},
      {"settle-speed", "after the push the sand is at rest below this rms speed, m/s",
       &m_config.settleSpeed, 0.0, 10.0},
      {"max-settle-seconds", "longest wait for the sand to stop after the push, s",
       &m_config.maxSettleSeconds, 0.0, 1e6},
      {"seed", "random seed of the berm", &m_config.seed, 0, 1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
  };
}

SceneBounds Bulldozer::bounds() const {
  const Vec3 half = bladeHalfExtents();
  const float back = bladeStart().x - half.x - (0.5f + kMargin) * d();
  const float halfAlong = 0.5f * static_cast<float>(m_config.berm[0] - 1) * spacing();
  const float bermFront = halfAlong + (kReach + kJitter) * d();
  // A berm pushed as a whole keeps about its length ahead of the blade; one that the blade cuts
  // through heaps up shorter.
  const float front =
      std::max(bladeFaceStart() + bladeTravel() + 2.0f * bermFront, bermFront) + kMargin * d();
  const float bermTop =
      bermLift() + static_cast<float>(m_config.berm[1] - 1) * spacing() + kReach * d();
  const float bladeTop = (kFloorClearance + m_config.bladeHeight) * d();
  const float top = std::max(bermTop, bladeTop) + kMargin * d();
  const float side = half.z + (0.5f + kMargin) * d();
  return {{back, 0.0f, -side}, {front, top, side}};
}

}  // namespace sandphys::scenes
