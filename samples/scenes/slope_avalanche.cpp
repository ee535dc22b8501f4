#include "scenes/slope_avalanche.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace sandphys::scenes {

namespace {

using kit::kJitter;
using kit::kReach;
// Gap between a wall and the nearest lattice centres, d: the reach and the jitter, with room.
constexpr float kWallGap = 1.4f;
// Room above the block's top inside the container, d.
constexpr float kHeadroom = 4.0f;

// The speed guard is the speed of a frictionless slide from the block's top to the run-out
// floor with this margin (rebounds, rim speed of spinning grains), and never below
// kMinGuardSpeed.
constexpr float kGuardMargin = 1.1f;
constexpr float kMinGuardSpeed = 2.0f;
// Substeps per Hertz contact time at the guard speed. The guard is the worst case, slower
// contacts last longer and get more substeps; 10 (the minimum is 8) halves the cost of the
// default 20, as the cylinder-pile settle test does.
constexpr float kStepsPerContact = 10.0f;
// After the release the sand needs a moment to pick up speed; before it, a calm world only means
// "not started yet", s.
constexpr double kMinRunSeconds = 0.25;

using C = SlopeAvalancheConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"slope-angle", &C::slopeAngle, "deg", 0.0, 60.0, "tilt of the slope from horizontal"},
    {"block", &C::block, "", 1, 1024, "granules along x (down the slope), y (layers), z (across)"},
    {"friction", &C::friction, "", 0.0, 10.0, "friction coefficient of the slope and the walls"},
    {"release-time", &C::releaseTime, "s", 0.0, 1e9, "earliest time the wall is removed"},
    {"slope-length", &C::slopeLength, "d", 0.0, 1e4, "horizontal length of the slope"},
    {"runout-length", &C::runoutLength, "d", 1.0, 1e4, "length of the flat floor beyond it"},
    {"moved-distance", &C::movedDistance, "d", 0.0, 1e4,
     "a granule has moved when this far from its place at release"},
    kit::settleSpeedParam(&C::settleSpeed),
    kit::maxSettleSecondsParam(&C::maxSettleSeconds),
    kit::seedParam(&C::seed),
    kit::diameterParam(&C::particleDiameter),
});

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

}  // namespace

std::span<const kit::Param<C>> SlopeAvalanche::table() const {
  return kTable;
}

std::uint32_t SlopeAvalanche::blockGranules() const {
  return m_config.block[0] * m_config.block[1] * m_config.block[2];
}

float SlopeAvalanche::tanAngle() const {
  return std::tan(radians(m_config.slopeAngle));
}

Vec3 SlopeAvalanche::downSlope() const {
  const float angle = radians(m_config.slopeAngle);
  return {std::cos(angle), -std::sin(angle), 0.0f};
}

float SlopeAvalanche::columnLift() const {
  // The lowest particle of a granule is at most kReach from its centre, measured normal to
  // the slope, which is cos(angle) of the vertical gap; the jitter moves a centre vertically and
  // along the slope (where the surface is tan(angle) higher per unit of x).
  const float cosAngle = std::cos(radians(m_config.slopeAngle));
  return (kReach / cosAngle + kJitter * (1.0f + tanAngle()) + 0.15f) * d();
}

float SlopeAvalanche::columnX(std::uint32_t i) const {
  return -(kWallGap + static_cast<float>(i) * kDefaultGranuleSpacing) * d();
}

SlopeAvalanche::Channel SlopeAvalanche::channel() const {
  Channel c{};
  c.back = columnX(m_config.block[0] - 1) - kWallGap * d();
  c.end = (m_config.slopeLength + m_config.runoutLength) * d();
  c.halfWidth =
      (0.5f * static_cast<float>(m_config.block[2] - 1) * kDefaultGranuleSpacing + kWallGap) * d();
  c.floor = -m_config.slopeLength * d() * tanAngle();
  const float blockHeight = static_cast<float>(m_config.block[1] - 1) * kDefaultGranuleSpacing;
  c.top = -c.back * tanAngle() + columnLift() + (blockHeight + kReach + kHeadroom) * d();
  return c;
}

WorldSettings SlopeAvalanche::worldSettings() const {
  WorldSettings settings;
  settings.particleDiameter = d();
  kit::reserveExactly(settings, name(), kit::granuleCount(m_config.block));
  const Channel c = channel();
  const float drop = c.top - c.floor;
  settings.maxSpeed =
      std::max(kMinGuardSpeed, kGuardMargin * std::sqrt(2.0f * gravityMagnitude(settings) * drop));
  settings.stepsPerContact = kStepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings);
  return settings;
}

void SlopeAvalanche::build(World& world) {
  m_course = kit::Course({.settleSpeed = m_config.settleSpeed,
                          .maxSettleSeconds = m_config.maxSettleSeconds,
                          .actAfter = m_config.releaseTime,
                          .minRestSeconds = kMinRunSeconds},
                         kit::granuleMass(world.settings()));

  const SurfaceMaterial surface{.friction = m_config.friction};
  const Channel c = channel();
  world.addCollider(
      Box{.center = {0.5f * (c.back + c.end), 0.5f * (c.floor + c.top), 0.0f},
          .halfExtents = {0.5f * (c.end - c.back), 0.5f * (c.top - c.floor), c.halfWidth},
          .inside = true,
          .material = surface});
  const float angle = radians(m_config.slopeAngle);
  world.addCollider(Plane{
      .normal = {std::sin(angle), std::cos(angle), 0.0f}, .offset = 0.0f, .material = surface});
  // Solid where x > 0 (Plane is solid where dot(normal, x) < offset).
  m_wall =
      world.addCollider(Plane{.normal = {-1.0f, 0.0f, 0.0f}, .offset = 0.0f, .material = surface});

  // One GranuleBlock per column across the slope, each resting on the slope beneath it; the x
  // spacing between columns alone keeps neighbours apart at any height difference.
  const float spacing = kDefaultGranuleSpacing * d();
  const float blockHeight = static_cast<float>(m_config.block[1] - 1) * spacing;
  for (std::uint32_t i = 0; i < m_config.block[0]; ++i) {
    const float x = columnX(i);
    world.addGranules(
        GranuleBlock{.center = {x, -x * tanAngle() + columnLift() + 0.5f * blockHeight, 0.0f},
                     .countX = 1,
                     .countY = m_config.block[1],
                     .countZ = m_config.block[2],
                     .spacing = spacing,
                     .seed = m_config.seed * 1000003u + i});
  }
  // Until the release, the metrics measure from the lattice (a sync point at setup only).
  m_reference = kit::Reference(world.readBodies());
}

void SlopeAvalanche::update(World& world, const StepReport& report, double simTime) {
  if (!m_course.update(report, simTime, blockGranules()) || !m_course.acting()) return;
  m_reference = kit::Reference(world.readBodies());
  // Beyond the end of the run-out, where no grain can reach it.
  world.setCollider(m_wall, Plane{.normal = {-1.0f, 0.0f, 0.0f},
                                  .offset = -(channel().end + 10.0f * d()),
                                  .material = {.friction = m_config.friction}});
  m_course.endAct(simTime);
}

std::string SlopeAvalanche::status() const {
  if (!released()) return "held";
  if (m_course.done()) return "came to rest";
  return "released at " + std::to_string(releasedAt()).substr(0, 5) + " s";
}

SceneView SlopeAvalanche::view(const std::optional<SceneBounds>& contents) const {
  SceneBounds focus = bounds();
  if (contents) focus.max.y = std::min(focus.max.y, contents->max.y + 4.0f * d());
  return {focus, 0.35f, 0.35f};
}

bool SlopeAvalanche::contains(const Vec3& centre) const {
  const Channel c = channel();
  const Vec3 n = {-downSlope().y, downSlope().x, 0.0f};  // the slope's upward normal
  return centre.x >= c.back && centre.x <= c.end && std::abs(centre.z) <= c.halfWidth &&
         centre.y >= c.floor && centre.y <= c.top && n.x * centre.x + n.y * centre.y >= 0.0f;
}

double SlopeAvalanche::comDisplacement(const kit::Reference& reference,
                                       std::span<const BodyState> bodies) const {
  const Vec3 s = downSlope();
  double sum = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : bodies) {
    const BodyState* before = body.granule && body.alive ? reference.before(body) : nullptr;
    if (!before) continue;
    sum +=
        (body.position.x - before->position.x) * s.x + (body.position.y - before->position.y) * s.y;
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

std::vector<SceneMetric> SlopeAvalanche::metrics(std::span<const BodyState> bodies) const {
  const double moved = m_config.movedDistance * d();
  double front = -std::numeric_limits<double>::infinity();
  double frontBefore = -std::numeric_limits<double>::infinity();
  std::size_t granules = 0;
  std::size_t movedCount = 0;
  for (const BodyState& body : bodies) {
    if (!body.granule || !body.alive) continue;
    ++granules;
    front = std::max(front, static_cast<double>(body.position.x));
    const BodyState* before = m_reference.before(body);
    if (!before) continue;
    const Vec3& p0 = before->position;
    frontBefore = std::max(frontBefore, static_cast<double>(p0.x));
    const double dx = body.position.x - p0.x;
    const double dy = body.position.y - p0.y;
    const double dz = body.position.z - p0.z;
    if (dx * dx + dy * dy + dz * dz > moved * moved) ++movedCount;
  }
  if (granules == 0) front = frontBefore = 0.0;
  const double com = comDisplacement(m_reference, bodies);
  return {
      {"granules", static_cast<double>(granules)},
      {"slope_angle_deg", m_config.slopeAngle},
      {"released", released() ? 1.0 : 0.0},
      {"release_time_s", releasedAt()},
      {"com_displacement_m", com},
      {"com_displacement_d", com / d()},
      // x is horizontal distance downhill from the retaining wall.
      {"front_x_m", front},
      {"front_x_d", front / d()},
      {"front_advance_d", (front - frontBefore) / d()},
      {"moved_fraction", granules ? static_cast<double>(movedCount) / granules : 0.0},
  };
}

SceneBounds SlopeAvalanche::bounds() const {
  const Channel c = channel();
  return {{c.back, c.floor, -c.halfWidth}, {c.end, c.top, c.halfWidth}};
}

}  // namespace sandphys::scenes
