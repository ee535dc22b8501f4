#include "scenes/cylinder_pile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "scenes/kit/checks.h"
#include "scenes/kit/course.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using C = CylinderPileConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"batches", &C::batches, "", 1, 4096, "batches dropped in total"},
    {"batch", &C::batch, "", 1, 1024, "granules per batch along x, y (layers), z"},
    {"spacing", &C::spacing, "d", 2.0, 10.0, "lattice spacing of a batch"},
    {"radius", &C::cylinderRadius, "d", 2.0, 1e4, "radius of the cylinder wall and the floor"},
    {"height", &C::cylinderHeight, "d", 1.0, 1e5, "height of the cylinder wall"},
    // Any lower and the first batch (reach 1.11 d) starts inside the floor (particles of 0.5 d).
    {"first-drop", &C::firstDropHeight, "d", 2.0, 1e5, "height of the first batch above the floor"},
    {"drop-gap", &C::dropGap, "d", 1.5, 1e5, "gap between the pile top and the next batch"},
    {"max-batch-seconds", &C::maxSecondsPerBatch, "s", 0.0, 1e6, "longest wait for a batch"},
});

// A run of `count` lattice columns along x, from x = first at z = row, in lattice spacings.
struct LatticeRun {
  std::int32_t row, first;
  std::uint32_t count;
};

// The `columns` columns of a square lattice nearest its axis (x = z = 0), as one run per row in
// z order: ties in distance go to the lower row, then the lower column, so that each row's share
// is one run.
std::vector<LatticeRun> discRuns(std::uint32_t columns) {
  const auto half = static_cast<std::int32_t>(std::ceil(std::sqrt(columns / 3.14159265))) + 2;
  std::vector<std::array<std::int32_t, 3>> sites;  // (x² + z², z, x)
  for (std::int32_t j = -half; j <= half; ++j) {
    for (std::int32_t i = -half; i <= half; ++i) sites.push_back({i * i + j * j, j, i});
  }
  std::sort(sites.begin(), sites.end());
  sites.resize(columns);
  std::sort(sites.begin(), sites.end(), [](const auto& a, const auto& b) {
    return std::tie(a[1], a[2]) < std::tie(b[1], b[2]);
  });
  std::vector<LatticeRun> runs;
  for (const auto& [r2, j, i] : sites) {
    if (runs.empty() || runs.back().row != j) runs.push_back({j, i, 0});
    ++runs.back().count;
  }
  return runs;
}

// Largest distance of a column of `runs` from the axis, in lattice spacings.
double discRadius(std::span<const LatticeRun> runs) {
  double farthest = 0.0;
  for (const LatticeRun& run : runs) {
    for (std::int32_t i : {run.first, run.first + std::int32_t(run.count) - 1}) {
      farthest = std::max(farthest, std::hypot(double(i), double(run.row)));
    }
  }
  return farthest;
}

}  // namespace

std::span<const kit::Param<C>> CylinderPile::table() const {
  return kTable;
}

float CylinderPile::batchReach() const {
  const double farthest = discRadius(discRuns(m_config.batch[0] * m_config.batch[2]));
  const double jitter = GranuleBlock{}.jitter * std::sqrt(2.0);
  return static_cast<float>(((farthest + jitter) * m_config.spacing + kGranuleReach) * d());
}

WorldSettings CylinderPile::worldSettings() const {
  const Config& c = m_config;
  // The top layer of a batch falls its drop height and the batch's height.
  const float fall =
      (std::max(c.firstDropHeight, c.dropGap) + kit::blockSpan(c.batch[1], c.spacing)) * d();
  // Every batch is allocated up front, as in the paper, and the rough floor.
  const WorldSettings settings = kit::worldSettings(
      name(), d(),
      {.granules = static_cast<std::uint64_t>(batchGranules()) * c.batches,
       .bodies = 1,
       .particles = roughFloorParticles(RoughFloor{.radius = c.cylinderRadius * d()}, d()),
       .maxSpeed = kit::pourGuardSpeed(0.0f, fall, kit::kGravity)});
  const float reach = batchReach();
  kit::require(reach <= c.cylinderRadius * d(), name(), "a batch reaches ", reach / d(),
               " d from the axis, outside the cylinder (radius ", c.cylinderRadius, " d)");
  return settings;
}

void CylinderPile::build(World& world) {
  m_batchesDropped = 0;
  m_settleTimes.clear();
  const ParticleTemplate granule = tetrahedronTemplate(d(), world.settings().material.density);
  m_granuleMass = granule.mass;
  m_granuleOuterRadius = granule.boundingRadius + 0.5f * d();
  kit::addCylinderContainer(world, m_config.cylinderRadius * d(), m_config.cylinderHeight * d(),
                            d());
  m_pileTop = 0.0f;
  dropBatch(world, m_config.firstDropHeight * d(), world.simulatedTime());
}

void CylinderPile::dropBatch(World& world, float bottomLayerY, double simTime) {
  const float spacing = m_config.spacing * d();
  const float blockHeight = kit::blockSpan(m_config.batch[1], spacing);
  std::uint64_t seed = m_config.seed * 1000003u + m_batchesDropped * 4099u;
  for (const LatticeRun& run : discRuns(m_config.batch[0] * m_config.batch[2])) {
    const float middle = static_cast<float>(run.first) + 0.5f * static_cast<float>(run.count - 1);
    world.addGranules(GranuleBlock{
        .center = {middle * spacing, bottomLayerY + 0.5f * blockHeight, run.row * spacing},
        .countX = run.count,
        .countY = m_config.batch[1],
        .countZ = 1,
        .spacing = spacing,
        .seed = seed++});
  }
  ++m_batchesDropped;
  // Calm means nothing until the top layer has fallen onto the pile (the gap and the batch's
  // height) and slid and bounced a while.
  const double fall = bottomLayerY - m_pileTop + blockHeight;
  const double g = length(world.settings().gravity);
  m_wait = {simTime, 1.5 * std::sqrt(2.0 * std::max(fall, 0.0) / g), m_config.maxSecondsPerBatch};
}

void CylinderPile::update(World& world, const StepReport& report, double simTime) {
  // The older batches are at rest: the world's kinetic energy is the newest batch's, per granule
  // of it (per granule of the whole pile, a large pile would call a batch settled too early).
  const bool calm = kit::granulesCalm(report, batchGranules(), m_granuleMass, m_config.settleSpeed);
  if (finished() || !m_wait.over(calm, simTime)) return;
  m_settleTimes.push_back(simTime - m_wait.start);
  if (finished()) return;
  m_pileTop = pileTop(world.readBodies());
  dropBatch(world, m_pileTop + m_config.dropGap * d(), simTime);
}

std::string CylinderPile::status() const {
  return "batch " + std::to_string(m_batchesDropped) + "/" + std::to_string(m_config.batches) +
         (finished() ? " settled" : "");
}

bool CylinderPile::contains(const Vec3& centre) const {
  const float radius = m_config.cylinderRadius * d();
  return centre.y >= 0.0f && centre.x * centre.x + centre.z * centre.z <= radius * radius;
}

float CylinderPile::pileTop(std::span<const BodyState> bodies) const {
  return kit::pileSurface(
      bodies, [this](const Vec3& centre) { return contains(centre); }, m_granuleOuterRadius);
}

std::vector<SceneMetric> CylinderPile::metrics(std::span<const BodyState> bodies) const {
  const float top = pileTop(bodies);
  const double settled = static_cast<double>(m_settleTimes.size());
  const double settleSum = std::accumulate(m_settleTimes.begin(), m_settleTimes.end(), 0.0);
  return {
      {"batches_dropped", static_cast<double>(m_batchesDropped)},
      {"batches_settled", settled},
      {"mean_settle_seconds", settled > 0.0 ? settleSum / settled : 0.0},
      {"pile_top_m", top},
      {"pile_top_d", top / d()},
  };
}

SceneBounds CylinderPile::bounds() const {
  const float r = m_config.cylinderRadius * d();
  return {{-r, -d(), -r}, {r, m_config.cylinderHeight * d(), r}};
}

}  // namespace sandphys::scenes
