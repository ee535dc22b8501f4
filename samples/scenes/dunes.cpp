#include "scenes/dunes.h"

#include <algorithm>
#include <cmath>
#include <ranges>

#include "scenes/kit/checks.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/pour.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using C = DunesConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"granules", &C::granules, "", 1, 1e8, "granules poured by each column"},
    {"separation", &C::separation, "d", 0.0, 1e4, "distance between the two columns"},
    {"outlet", &C::outlet, "d", 0.5, 1e4, "width of each emitter's square"},
    {"rate", &C::rate, "granules/s", 1.0, 1e5, "pour rate of each column"},
    {"pour-height", &C::pourHeight, "d", 1.0, 1e4, "height of the emitters above the floor"},
    {"floor-half-length", &C::floorHalfLength, "d", 2.0, 1e4, "half length of the floor along x"},
    {"floor-half-width", &C::floorHalfWidth, "d", 2.0, 1e4, "half width of the floor along z"},
});

}  // namespace

std::span<const kit::Param<C>> Dunes::table() const {
  return kTable;
}

WorldSettings Dunes::worldSettings() const {
  const Config& c = m_config;
  kit::require(0.5f * c.separation + 0.5f * c.outlet + kit::kReach <= c.floorHalfLength &&
                   0.5f * c.outlet + kit::kReach <= c.floorHalfWidth,
               name(), "the columns (separation ", c.separation, " d, outlet ", c.outlet,
               " d) reach past the floor (floor-half-length ", c.floorHalfLength,
               " d, floor-half-width ", c.floorHalfWidth, " d)");
  pour().checkAboveFloor(name());
  return kit::worldSettings(name(), d(),
                            {.granules = 2ull * c.granules,
                             .bodies = 1,
                             .particles = roughFloorParticles(roughFloor(), d()),
                             .maxSpeed = pour().guardSpeed(),
                             .stepsPerContact = c.stepsPerContact,
                             .youngsModulus = c.youngsModulus,
                             .friction = c.friction});
}

void Dunes::build(World& world) {
  m_profile = {};
  m_course = kit::PourCourse(pour().course(m_config.settleSpeed, m_config.maxSettleSeconds,
                                           length(world.settings().gravity)),
                             kit::granuleMass(world.settings()), 2 * m_config.granules);
  const RoughFloor floor = roughFloor();
  world.addRoughFloor(floor);
  world.addSink(pour().sink(std::max(floor.halfExtentX, floor.halfExtentZ)));
  for (int side : {-1, 1}) {
    const float x = static_cast<float>(side) * 0.5f * m_config.separation * d();
    // Two different streams of orientations.
    world.addEmitter(pour().emitter(x, m_config.seed * 2 + (side > 0 ? 1 : 0)));
  }
}

RoughFloor Dunes::roughFloor() const {
  return RoughFloor{.halfExtentX = m_config.floorHalfLength * d(),
                    .halfExtentZ = m_config.floorHalfWidth * d(),
                    .spacing = d()};
}

void Dunes::update(World& world, const StepReport& report, double simTime) {
  m_course.count(world, simTime);
  // Once per run, when the sand has settled: the profile for series().
  if (m_course.update(report, simTime)) m_profile = profile(world.readBodies());
}

bool Dunes::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::abs(centre.x) <= m_config.floorHalfLength * d() &&
         std::abs(centre.z) <= m_config.floorHalfWidth * d();
}

Dunes::Profile Dunes::profile(std::span<const BodyState> bodies) const {
  const double strip = 2.0 * kGranuleReach * d();
  const double halfLength = m_config.floorHalfLength * d();
  const auto strips = static_cast<std::size_t>(std::ceil(2.0 * halfLength / strip));
  // The highest [x, height] of each strip; an empty strip keeps its height of -1.
  std::vector<std::array<double, 2>> top(strips, {0.0, -1.0});
  for (const BodyState& body : kit::granulesIn(bodies)) {
    const Vec3& c = body.position;
    if (!contains(c) || std::abs(c.z) > strip) continue;
    const auto i = std::min(strips - 1, static_cast<std::size_t>((c.x + halfLength) / strip));
    const double h = c.y - 0.5 * d();  // above the floor particles' tops
    if (h > top[i][1]) top[i] = {c.x, h};
  }
  Profile p;
  for (const auto& point : top) {
    if (point[1] < 0.0) continue;
    p.points.push_back(point);
    auto& crest = point[0] < 0.0 ? p.leftCrest : p.rightCrest;
    if (point[1] > crest[1]) crest = point;
  }
  auto between = p.points | std::views::filter([&](const auto& point) {
                   return point[0] > p.leftCrest[0] && point[0] < p.rightCrest[0];
                 });
  const auto lowest = std::ranges::min_element(between, {}, [](const auto& q) { return q[1]; });
  if (lowest != between.end()) p.saddle = *lowest;
  return p;
}

std::vector<SceneMetric> Dunes::metrics(std::span<const BodyState> bodies) const {
  const Profile p = profile(bodies);
  std::uint32_t onFloor = 0;
  for (const BodyState& b : kit::granulesIn(bodies)) onFloor += contains(b.position);
  return {
      {"granules_poured", static_cast<double>(m_course.poured())},
      {"granules_on_floor", static_cast<double>(onFloor)},
      {"left_crest_height_d", p.leftCrest[1] / d()},
      {"left_crest_x_d", p.leftCrest[0] / d()},
      {"right_crest_height_d", p.rightCrest[1] / d()},
      {"right_crest_x_d", p.rightCrest[0] / d()},
      {"saddle_height_d", p.saddle[1] / d()},
      {"saddle_x_d", p.saddle[0] / d()},
      {"saddle_depth_d", (std::min(p.leftCrest[1], p.rightCrest[1]) - p.saddle[1]) / d()},
      {"crest_separation_d", (p.rightCrest[0] - p.leftCrest[0]) / d()},
      {"settled", m_course.calm() ? 1.0 : 0.0},
  };
}

std::vector<SceneSeries> Dunes::series() const {
  SceneSeries profile{.name = "dune_profile"};
  for (const auto& [x, h] : m_profile.points) profile.points.push_back({x / d(), h / d()});
  return {profile};
}

SceneBounds Dunes::bounds() const {
  return pour().bounds(m_config.floorHalfLength * d(), m_config.floorHalfWidth * d());
}

}  // namespace sandphys::scenes
