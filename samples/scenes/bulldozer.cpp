#include "scenes/bulldozer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kJitter;
using kit::kReach;
// Between the blade's particles and the floor, d: the blade's force must be the sand's alone,
// and a grain (at least d across) must not pass beneath it.
constexpr float kFloorClearance = 0.25f;
// Between the centres of the blade's front and back particles, d: the two sheets touch.
constexpr float kBladeThickness = 1.0f;
// Room around the scene's contents in the bounds, d.
constexpr float kMargin = 2.0f;
// How far beyond the bounds a grain may roll on the floor before it counts as lost, d.
constexpr float kRoam = 20.0f;
// The speed guard is this multiple of the blade's speed (grains thrown off its face outrun it)
// and at least kit::kMinGuardSpeed, for the berm's settling drop. blade-speed stops at 5 m/s: a
// faster blade needs a guard, and so a time step, that would make the scene crawl.
constexpr float kGuardPerBladeSpeed = 4.0f;
// After the push the sand needs a moment to show whether it keeps moving, s.
constexpr double kMinRestSeconds = 0.1;

using C = BulldozerConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"berm", &C::berm, "", 1, 1024,
     "granules of the berm along x (the push), y (layers), z (across)"},
    {"blade-speed", &C::bladeSpeed, "m/s", 0.0, 5.0,
     "speed of the blade during the push; at 0 it stays put"},
    {"push-distance", &C::pushDistance, "d", 0.0, 1e4, "distance the blade travels"},
    {"push-start", &C::pushStart, "s", 0.0, 1e6,
     "time the push starts; the berm settles until then"},
    {"gap", &C::gap, "d", 0.0, 1e3, "gap between the blade and the berm at the start"},
    {"blade-height", &C::bladeHeight, "d", 2.0, 1e3,
     "height of the blade, at least 2 so that its box is not flat"},
    {"blade-overhang", &C::bladeOverhang, "d", 0.0, 1e3,
     "how far the blade reaches beyond the berm on each side"},
    {"floor-friction", &C::floorFriction, "", 0.0, 10.0, "friction coefficient of the floor"},
});

}  // namespace

std::span<const kit::Param<C>> Bulldozer::table() const {
  return kTable;
}

float Bulldozer::bermLift() const {
  return (kReach + kJitter + 0.15f) * d();
}

Vec3 Bulldozer::bladeHalfExtents() const {
  // Particle centres lie on the box, so its faces are half a diameter inside the blade's.
  return {0.5f * kBladeThickness * d(), 0.5f * (m_config.bladeHeight - 1.0f) * d(),
          0.5f * kit::blockSpan(m_config.berm[2], spacing()) + m_config.bladeOverhang * d()};
}

float Bulldozer::bladeFaceStart() const {
  return -0.5f * kit::blockSpan(m_config.berm[0], spacing()) -
         (kReach + kJitter + m_config.gap) * d();
}

Vec3 Bulldozer::bladeStart() const {
  const Vec3 half = bladeHalfExtents();
  return {bladeFaceStart() - 0.5f * d() - half.x, (kFloorClearance + 0.5f) * d() + half.y, 0.0f};
}

float Bulldozer::bladeTravel() const {
  return m_config.bladeSpeed > 0.0f ? m_config.pushDistance * d() : 0.0f;
}

TriangleMesh Bulldozer::bladeMesh() const {
  const Vec3 half = bladeHalfExtents();
  TriangleMesh box = boxMesh(-half, half);
  box.source = "bulldozer blade";
  return box;
}

SampledMesh Bulldozer::bladeShape() const {
  return sampleMesh(bladeMesh(), d());
}

WorldSettings Bulldozer::worldSettings() const {
  return kit::worldSettings(
      name(), d(),
      {.granules = kit::granuleCount(m_config.berm),
       .bodies = 1,
       .particles = bladeShape().centres.size(),
       .maxSpeed = std::max(kit::kMinGuardSpeed, kGuardPerBladeSpeed * m_config.bladeSpeed),
       .stepsPerContact = kit::kGuardStepsPerContact});
}

void Bulldozer::build(World& world) {
  m_phase = Phase::Waiting;
  m_course = kit::Course({.settleSpeed = m_config.settleSpeed,
                          .maxSettleSeconds = m_config.maxSettleSeconds,
                          .minRestSeconds = kMinRestSeconds,
                          .actFirst = true},
                         kit::granuleMass(world.settings()));
  for (BladeLoad& load : m_loads) load = {};
  m_drag.clear();
  m_atPushStart.clear();
  m_atPushEnd.clear();
  m_stepsRun = 0;
  m_timeStep = world.timeStep();

  world.addCollider(Plane{.normal = {0.0f, 1.0f, 0.0f},
                          .offset = 0.0f,
                          .material = {.friction = m_config.floorFriction}});
  world.addGranules(kit::blockAbove(bermLift(), m_config.berm, spacing(), m_config.seed));
  const Vec3 start = bladeStart();
  const SampledMesh blade = bladeShape();
  m_blade = world.addBody(blade.shape, BodyDesc{.position = start, .motion = Motion::Kinematic});
  m_surfaces = {surfaceOf(m_blade, bladeMesh(), blade, BodyMaterial::Metal)};

  // A blade that does not move gets a move in place, so that the push still starts at a substep.
  const float travel = bladeTravel();
  const KinematicMovePlan push = world.moveKinematic(
      m_blade,
      KinematicMove{
          .from = start,
          .to = start + Vec3{travel, 0.0f, 0.0f},
          .startTime = m_config.pushStart,
          .duration = travel > 0.0f ? static_cast<double>(travel) / m_config.bladeSpeed : 0.0});
  m_pushStartStep = push.startStep;
  m_pushSteps = travel > 0.0f ? push.endStep - push.startStep : 0;
  m_reference = kit::Reference(world.readBodies());  // the lattice, until the push starts
}

void Bulldozer::readLoad(World& world) {
  const std::optional<BodyForce> force = kit::takeForceOn(world, m_blade);
  if (!force || force->substeps == 0) return;
  BladeLoad& load = m_loads[static_cast<int>(m_phase)];
  load.impulse[0] += static_cast<double>(force->force.x) * m_timeStep;
  load.impulse[1] += static_cast<double>(force->force.y) * m_timeStep;
  load.substeps += force->substeps;
  // 0 - x rather than -x: no "-0" drag in the metrics of a blade that never touched sand.
  m_drag.push_back({world.simulatedTime(), 0.0f - force->meanForce().x, m_phase});
}

std::uint64_t Bulldozer::phaseEnd() const {
  if (m_phase == Phase::Waiting) return m_pushStartStep;
  if (m_phase == Phase::Pushing) return m_pushStartStep + m_pushSteps;
  return std::numeric_limits<std::uint64_t>::max();
}

void Bulldozer::endPhases(World& world) {
  // A phase's force is read before the next one's substeps add to it.
  while (m_phase != Phase::Stopped && world.stepCount() >= phaseEnd()) {
    readLoad(world);
    if (m_phase == Phase::Waiting) {
      m_atPushStart = world.readBodies();
      m_reference = kit::Reference(m_atPushStart);
      m_phase = Phase::Pushing;
    } else {
      m_atPushEnd = world.readBodies();
      m_course.endAct(world.simulatedTime());
      m_phase = Phase::Stopped;
    }
  }
}

StepReport Bulldozer::step(World& world, float frameDt) {
  if (!m_blade.isValid()) return world.step(frameDt);
  endPhases(world);
  // The World stops where the current phase ends and holds the rest of the frame for the next.
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
  m_course.update(report, simTime, static_cast<std::uint32_t>(kit::granuleCount(m_config.berm)));
}

std::string Bulldozer::status() const {
  if (m_phase == Phase::Waiting) return "settling";
  if (m_phase == Phase::Stopped) return m_course.done() ? "stopped, sand at rest" : "stopped";
  const double done = static_cast<double>(std::min(m_stepsRun - m_pushStartStep, m_pushSteps));
  const double travelled =
      m_pushSteps > 0 ? m_config.pushDistance * done / static_cast<double>(m_pushSteps) : 0.0;
  char text[96];
  std::snprintf(text, sizeof text, "pushing %.1f/%.0f d, drag %.2f N", travelled,
                m_config.pushDistance, m_drag.empty() ? 0.0f : m_drag.back().drag);
  return text;
}

bool Bulldozer::contains(const Vec3& centre) const {
  // The floor has no edge: a grain is lost only below it or far beyond the bounds.
  const SceneBounds b = bounds();
  const float roam = kRoam * d();
  return centre.y >= 0.0f && centre.y <= b.max.y && centre.x >= b.min.x - roam &&
         centre.x <= b.max.x + roam && std::abs(centre.z) <= b.max.z + roam;
}

std::vector<SceneMetric> Bulldozer::metrics(std::span<const BodyState> bodies) const {
  float bermFront = -std::numeric_limits<float>::infinity();
  for (const BodyState& body : m_reference.bodies()) {
    if (body.granule) bermFront = std::max(bermFront, body.position.x);
  }
  double shift = 0.0;
  std::size_t granules = 0;
  std::size_t matched = 0;
  std::size_t ahead = 0;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    ++granules;
    if (body.position.x > bermFront) ++ahead;
    if (const BodyState* before = m_reference.before(body)) {
      shift += body.position.x - before->position.x;
      ++matched;
    }
  }
  if (matched > 0) shift /= static_cast<double>(matched);

  const BladeLoad& push = load(Phase::Pushing);
  const double pushSeconds = static_cast<double>(push.substeps) * m_timeStep;
  float peak = 0.0f;
  for (const DragSample& sample : m_drag) {
    if (sample.phase == Phase::Pushing) peak = std::max(peak, sample.drag);
  }
  const BodyState* blade = kit::findBody(bodies, m_blade);
  const double travel = (blade ? blade->position.x : bladeStart().x) - bladeStart().x;
  return {
      {"granules", static_cast<double>(granules)},
      {"blade_travel_m", travel},
      {"blade_travel_d", travel / d()},
      {"push_seconds", pushSeconds},
      // Against the push, over the push, N s.
      {"drag_impulse_ns", 0.0 - push.impulse[0]},
      {"drag_mean_n", pushSeconds > 0.0 ? (0.0 - push.impulse[0]) / pushSeconds : 0.0},
      {"drag_peak_n", peak},
      // After the push: the sand leaning on the stopped blade.
      {"drag_now_n", m_drag.empty() ? 0.0 : m_drag.back().drag},
      {"com_shift_m", shift},
      {"com_shift_d", shift / d()},
      {"berm_front_x_m", bermFront},
      {"pushed_fraction",
       granules > 0 ? static_cast<double>(ahead) / static_cast<double>(granules) : 0.0},
  };
}

std::vector<SceneBody> Bulldozer::bodies(const World& world) const {
  if (!m_blade.isValid()) return {};
  return {kit::sceneBody("blade", world.readBody(m_blade))};
}

SceneBounds Bulldozer::bounds() const {
  const Vec3 half = bladeHalfExtents();
  const float back = bladeStart().x - half.x - (0.5f + kMargin) * d();
  const float bermFront =
      0.5f * kit::blockSpan(m_config.berm[0], spacing()) + (kReach + kJitter) * d();
  // A berm pushed as a whole keeps about its length ahead of the blade; one that the blade cuts
  // through heaps up shorter.
  const float front =
      std::max(bladeFaceStart() + bladeTravel() + 2.0f * bermFront, bermFront) + kMargin * d();
  const float bermTop = bermLift() + kit::blockSpan(m_config.berm[1], spacing()) + kReach * d();
  const float bladeTop = (kFloorClearance + m_config.bladeHeight) * d();
  const float top = std::max(bermTop, bladeTop) + kMargin * d();
  const float side = half.z + (0.5f + kMargin) * d();
  return {{back, 0.0f, -side}, {front, top, side}};
}

}  // namespace sandphys::scenes
