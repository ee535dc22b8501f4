#include "scenes/cylinder_pile.h"

#include "scenes/pour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sandphys::scenes {

namespace {

// Fraction of a fall's free-flight time added before a batch may count as settled: after landing
// the grains still slide and bounce for a while before the energy test means anything.
constexpr double kLandingMargin = 0.5;

}  // namespace

std::uint32_t CylinderPile::batchGranules() const {
  return m_config.batch[0] * m_config.batch[1] * m_config.batch[2];
}

std::vector<CylinderPile::FootprintRow> CylinderPile::footprint() const {
  const std::uint32_t columns = m_config.batch[0] * m_config.batch[2];
  // Candidate columns in a square comfortably larger than the disc, nearest the axis first; ties
  // by row and then column, so that every row's share is one contiguous run.
  const auto half = static_cast<std::int32_t>(std::ceil(std::sqrt(columns / 3.14159265))) + 2;
  struct Site {
    std::int32_t i, j;
  };
  std::vector<Site> sites;
  for (std::int32_t j = -half; j <= half; ++j) {
    for (std::int32_t i = -half; i <= half; ++i) sites.push_back({i, j});
  }
  std::sort(sites.begin(), sites.end(), [](const Site& a, const Site& b) {
    const std::int32_t ra = a.i * a.i + a.j * a.j;
    const std::int32_t rb = b.i * b.i + b.j * b.j;
    if (ra != rb) return ra < rb;
    return a.j != b.j ? a.j < b.j : a.i < b.i;
  });
  sites.resize(columns);
  std::sort(sites.begin(), sites.end(),
            [](const Site& a, const Site& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
  std::vector<FootprintRow> rows;
  for (const Site& site : sites) {
    if (rows.empty() || rows.back().row != site.j) {
      rows.push_back({site.j, site.i, 0});
    }
    ++rows.back().columns;
  }
  return rows;
}

float CylinderPile::batchReach() const {
  double farthest = 0.0;
  for (const FootprintRow& row : footprint()) {
    for (std::int32_t i : {row.firstColumn, row.firstColumn + std::int32_t(row.columns) - 1}) {
      farthest = std::max(farthest, std::hypot(double(i), double(row.row)));
    }
  }
  const double jitter = GranuleBlock{}.jitter * std::sqrt(2.0);
  return static_cast<float>(((farthest + jitter) * m_config.spacing + kGranuleReach) * d());
}

WorldSettings CylinderPile::worldSettings() const {
  WorldSettings settings;
  settings.particleDiameter = d();
  const std::uint64_t granules = static_cast<std::uint64_t>(batchGranules()) * m_config.batches;
  const std::uint64_t floorParticles =
      roughFloorParticles(RoughFloor{.radius = m_config.cylinderRadius * d()}, d());
  const std::uint64_t particles = 4 * granules + floorParticles;
  if (particles > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("cylinder-pile: batches × batch = " + std::to_string(granules) +
                          " granules need " + std::to_string(particles) +
                          " particles, more than a World can index (limit " +
                          std::to_string(std::numeric_limits<std::uint32_t>::max()) + ")");
  }
  if (batchReach() > m_config.cylinderRadius * d()) {
    throw InvalidArgument("cylinder-pile: a batch of " + std::to_string(m_config.batch[0]) + "×" +
                          std::to_string(m_config.batch[2]) + " columns at spacing " +
                          std::to_string(m_config.spacing) + " d reaches " +
                          std::to_string(batchReach() / d()) +
                          " d from the axis, outside the cylinder (radius " +
                          std::to_string(m_config.cylinderRadius) + " d)");
  }
  // Every batch is allocated up front, as in the paper: adding a batch never reallocates.
  settings.maxBodies = static_cast<std::uint32_t>(granules + 1);  // + the rough floor
  settings.maxParticles = static_cast<std::uint32_t>(particles);
  // The top layer of a batch falls its drop height and the batch's height.
  const float blockHeight = static_cast<float>(m_config.batch[1] - 1) * m_config.spacing;
  const float fall = (std::max(m_config.firstDropHeight, m_config.dropGap) + blockHeight) * d();
  settings.maxSpeed = pourGuardSpeed(0.0f, fall, gravityMagnitude(settings));
  settings.material.youngsModulus = sceneYoungsModulus(settings);
  return settings;
}

void CylinderPile::build(World& world) {
  m_batchesDropped = 0;
  m_settleTimes.clear();
  m_finished = false;
  const ParticleTemplate granule = tetrahedronTemplate(d(), world.settings().material.density);
  m_granuleMass = granule.mass;
  m_granuleOuterRadius = granule.boundingRadius + 0.5f * d();

  const float radius = m_config.cylinderRadius * d();
  world.addCollider(Cylinder{
      .base = {0.0f, 0.0f, 0.0f}, .radius = radius, .height = m_config.cylinderHeight * d()});
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d()});
  // Safety net one diameter under the rough floor: a grain that slips through the lattice (it
  // should not) rests there instead of falling forever and being integrated at maxSpeed.
  world.addCollider(Plane{.normal = {0.0f, 1.0f, 0.0f}, .offset = -d()});

  m_pileTop = 0.0f;
  dropBatch(world, m_config.firstDropHeight * d(), world.simulatedTime());
}

void CylinderPile::dropBatch(World& world, float bottomLayerY, double simTime) {
  const float spacing = m_config.spacing * d();
  const float blockHeight = static_cast<float>(m_config.batch[1] - 1) * spacing;
  const float centreY = bottomLayerY + 0.5f * blockHeight;
  // A batch is added row by row; check the room for all of it first so that it is all or nothing.
  const std::uint64_t granules = batchGranules();
  if (world.bodyCount() + granules > world.bodyCapacity() ||
      world.particleCount() + 4 * granules > world.particleCapacity()) {
    throw CapacityExceeded("cylinder-pile: batch " + std::to_string(m_batchesDropped + 1) +
                           " needs " + std::to_string(granules) + " bodies and " +
                           std::to_string(4 * granules) + " particles, the world has room for " +
                           std::to_string(world.bodyCapacity() - world.bodyCount()) + " and " +
                           std::to_string(world.particleCapacity() - world.particleCount()) +
                           " (create it from CylinderPile::settings())");
  }
  // One GranuleBlock per row of the footprint; each gets its own seed so that rows differ.
  std::uint64_t seed = m_config.seed * 1000003u + m_batchesDropped * 4099u;
  for (const FootprintRow& row : footprint()) {
    const float middle =
        static_cast<float>(row.firstColumn) + 0.5f * static_cast<float>(row.columns - 1);
    world.addGranules(GranuleBlock{.center = {middle * spacing, centreY, row.row * spacing},
                                   .countX = row.columns,
                                   .countY = m_config.batch[1],
                                   .countZ = 1,
                                   .spacing = spacing,
                                   .seed = seed++});
  }
  ++m_batchesDropped;
  m_lastDropTime = simTime;
  // The top layer falls onto the pile last; it has to fall the gap plus the block's height.
  const double fall = bottomLayerY - m_pileTop + blockHeight;
  m_minSettleTime = (1.0 + kLandingMargin) *
                    std::sqrt(2.0 * std::max(fall, 0.0) / gravityMagnitude(world.settings()));
}

void CylinderPile::update(World& world, const StepReport& report, double simTime) {
  if (m_finished) return;
  const double sinceDrop = simTime - m_lastDropTime;
  if (sinceDrop < m_minSettleTime) return;

  // Energy per granule of the newest batch: the older batches are at rest, so the world's kinetic
  // energy is essentially the newest batch's; dividing by all granules would call a batch settled
  // too early once the pile is large.
  const bool calm = granulesCalm(report, batchGranules(), m_granuleMass, m_config.settleSpeed);
  if (!calm && sinceDrop < m_config.maxSecondsPerBatch) return;

  m_settleTimes.push_back(sinceDrop);
  if (m_batchesDropped >= m_config.batches) {
    m_finished = true;
    return;
  }
  // One read-back per batch (a sync point), never per frame.
  const std::vector<BodyState> bodies = world.readBodies();
  m_pileTop = pileTop(bodies);
  dropBatch(world, m_pileTop + m_config.dropGap * d(), simTime);
}

std::string CylinderPile::status() const {
  std::string text =
      "batch " + std::to_string(m_batchesDropped) + "/" + std::to_string(m_config.batches);
  if (m_finished) text += " settled";
  return text;
}

bool CylinderPile::contains(const Vec3& centre) const {
  const float radius = m_config.cylinderRadius * d();
  return centre.y >= 0.0f && centre.x * centre.x + centre.z * centre.z <= radius * radius;
}

float CylinderPile::pileTop(std::span<const BodyState> bodies) const {
  // The outer radius is only known after build(); before it the centre height has to do.
  return pileSurface(
      bodies, [this](const Vec3& centre) { return contains(centre); }, m_granuleOuterRadius);
}

std::vector<SceneMetric> CylinderPile::metrics(std::span<const BodyState> bodies) const {
  const float top = pileTop(bodies);
  double settleSum = 0.0;
  for (double t : m_settleTimes) settleSum += t;
  return {
      {"batches", static_cast<double>(m_config.batches)},
      {"batches_dropped", static_cast<double>(m_batchesDropped)},
      {"batches_settled", static_cast<double>(m_settleTimes.size())},
      {"batch_granules", static_cast<double>(batchGranules())},
      {"mean_settle_seconds",
       m_settleTimes.empty() ? 0.0 : settleSum / static_cast<double>(m_settleTimes.size())},
      {"pile_top_m", top},
      {"pile_top_d", top / d()},
      {"cylinder_radius_m", m_config.cylinderRadius * d()},
      {"cylinder_height_m", m_config.cylinderHeight * d()},
  };
}

std::vector<SceneParameter> CylinderPile::parameters() {
  return {
      {"batches", "batches dropped in total", &m_config.batches, 1, 4096},
      {"batch", "granules per batch along x, y (layers), z", &m_config.batch, 1, 1024},
      {"seed", "random seed of the jitter and orientations", &m_config.seed, 0,
       1.8446744073709552e19},
      {"diameter", "particle diameter d, m", &m_config.particleDiameter, 1e-4, 1.0},
      {"spacing", "lattice spacing of a batch, d", &m_config.spacing, 2.0, 10.0},
      {"radius", "radius of the cylinder wall and the rough floor, d", &m_config.cylinderRadius,
       2.0, 1e4},
      {"height", "height of the cylinder wall, d", &m_config.cylinderHeight, 1.0, 1e5},
      // A granule reaches 1.11 d from its centre and a floor particle 0.5 d from the floor: any
      // lower and the first batch starts inside the floor.
      {"first-drop", "height of the first batch's lowest layer above the floor, d",
       &m_config.firstDropHeight, 2.0, 1e5},
      {"drop-gap", "gap between the pile top and the next batch, d", &m_config.dropGap, 1.5, 1e5},
      {"settle-speed", "a batch has settled below this rms speed, m/s", &m_config.settleSpeed, 0.0,
       10.0},
      {"max-batch-seconds", "longest wait for a batch to settle, s", &m_config.maxSecondsPerBatch,
       0.0, 1e6},
  };
}

SceneBounds CylinderPile::bounds() const {
  const float r = m_config.cylinderRadius * d();
  return {{-r, -d(), -r}, {r, m_config.cylinderHeight * d(), r}};
}

}  // namespace sandphys::scenes
