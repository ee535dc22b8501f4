#include "scenes/slope_avalanche.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

// Room above the block's top inside the container, d.
constexpr float kHeadroom = 4.0f;
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
});

}  // namespace

std::span<const kit::Param<C>> SlopeAvalanche::table() const {
  return kTable;
}

float SlopeAvalanche::angle() const {
  return m_config.slopeAngle * std::numbers::pi_v<float> / 180.0f;
}

Vec3 SlopeAvalanche::downSlope() const {
  return {std::cos(angle()), -std::sin(angle()), 0.0f};
}

Vec3 SlopeAvalanche::slopeNormal() const {
  return {std::sin(angle()), std::cos(angle()), 0.0f};
}

float SlopeAvalanche::columnLift() const {
  // The lowest particle of a granule is at most kReach from its centre, measured normal to
  // the slope, which is cos(angle) of the vertical gap; the jitter moves a centre vertically and
  // along the slope (where the surface is tan(angle) higher per unit of x).
  return (kit::kReach / std::cos(angle()) + kit::kJitter * (1.0f + std::tan(angle())) + 0.15f) *
         d();
}

float SlopeAvalanche::columnX(std::uint32_t i) const {
  return -(kit::kLatticeGap + static_cast<float>(i) * kDefaultGranuleSpacing) * d();
}

SceneBounds SlopeAvalanche::bounds() const {
  const float back = columnX(m_config.block[0] - 1) - kit::kLatticeGap * d();
  const float halfWidth =
      (0.5f * static_cast<float>(m_config.block[2] - 1) * kDefaultGranuleSpacing +
       kit::kLatticeGap) *
      d();
  const float layers = static_cast<float>(m_config.block[1] - 1) * kDefaultGranuleSpacing;
  const float tan = std::tan(angle());
  return {{back, -m_config.slopeLength * d() * tan, -halfWidth},
          {(m_config.slopeLength + m_config.runoutLength) * d(),
           -back * tan + columnLift() + (layers + kit::kReach + kHeadroom) * d(), halfWidth}};
}

WorldSettings SlopeAvalanche::worldSettings() const {
  const SceneBounds box = bounds();
  // A slide from the block's top to the run-out floor.
  return kit::worldSettings(name(), d(),
                            {.granules = kit::granuleCount(m_config.block),
                             .maxSpeed = kit::fallGuardSpeed(box.max.y - box.min.y),
                             .stepsPerContact = kit::kGuardStepsPerContact});
}

void SlopeAvalanche::build(World& world) {
  m_course = kit::Course({.settleSpeed = m_config.settleSpeed,
                          .maxSettleSeconds = m_config.maxSettleSeconds,
                          .actAfter = m_config.releaseTime,
                          .minRestSeconds = kMinRunSeconds},
                         kit::granuleMass(world.settings()));

  const SurfaceMaterial surface{.friction = m_config.friction};
  world.addCollider(kit::containerBox(bounds(), surface));
  world.addCollider(Plane{.normal = slopeNormal(), .offset = 0.0f, .material = surface});
  // Solid where x > 0 (Plane is solid where dot(normal, x) < offset).
  m_wall =
      world.addCollider(Plane{.normal = {-1.0f, 0.0f, 0.0f}, .offset = 0.0f, .material = surface});

  // One GranuleBlock per column across the slope, each resting on the slope beneath it; the x
  // spacing between columns alone keeps neighbours apart at any height difference.
  const float spacing = kDefaultGranuleSpacing * d();
  const float halfHeight = 0.5f * kit::blockSpan(m_config.block[1], spacing);
  for (std::uint32_t i = 0; i < m_config.block[0]; ++i) {
    const float x = columnX(i);
    world.addGranules(
        GranuleBlock{.center = {x, -x * std::tan(angle()) + columnLift() + halfHeight, 0.0f},
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
  const auto granules = static_cast<std::uint32_t>(kit::granuleCount(m_config.block));
  if (!m_course.update(report, simTime, granules) || !m_course.acting()) return;
  m_reference = kit::Reference(world.readBodies());
  // Beyond the end of the run-out, where no grain can reach it.
  world.setCollider(m_wall, Plane{.normal = {-1.0f, 0.0f, 0.0f},
                                  .offset = -(bounds().max.x + 10.0f * d()),
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
  return kit::inBounds(bounds(), centre) && dot(slopeNormal(), centre) >= 0.0f;
}

std::vector<SceneMetric> SlopeAvalanche::metrics(std::span<const BodyState> bodies) const {
  const double moved = m_config.movedDistance * d();
  double front = -std::numeric_limits<double>::infinity();
  double frontBefore = -std::numeric_limits<double>::infinity();
  std::size_t granules = 0;
  std::size_t movedCount = 0;
  for (const BodyState& body : kit::granulesIn(bodies)) {
    ++granules;
    front = std::max(front, static_cast<double>(body.position.x));
    const BodyState* before = m_reference.before(body);
    if (!before) continue;
    frontBefore = std::max(frontBefore, static_cast<double>(before->position.x));
    const double dx = body.position.x - before->position.x;
    const double dy = body.position.y - before->position.y;
    const double dz = body.position.z - before->position.z;
    if (dx * dx + dy * dy + dz * dz > moved * moved) ++movedCount;
  }
  if (granules == 0) front = frontBefore = 0.0;
  const double com = kit::meanDisplacement(m_reference, bodies, downSlope());
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

}  // namespace sandphys::scenes
