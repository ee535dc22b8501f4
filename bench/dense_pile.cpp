#include "dense_pile.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sandphys::bench {

namespace {

// A lattice column of the pile, in units of the spacing.
struct Site {
  std::int32_t i = 0;  // along x
  std::int32_t j = 0;  // along z
};

// A run of consecutive columns i = firstColumn.. in one row j: one GranuleBlock.
struct Run {
  std::int32_t row = 0;
  std::int32_t firstColumn = 0;
  std::uint32_t columns = 0;
};

// Gap left between the floor particles' tops and the lowest granule surface, d: enough that no
// jittered granule starts touching the floor.
constexpr float kFloorClearance = 0.05f;
// Room left above the initial column when the wall has to be raised, d (then rounded up to 10 d).
constexpr float kWallHeadroom = 5.0f;

// Columns whose granules stay inside the wall for any orientation and jitter, nearest the axis
// first (ties by row, then column), so that a partial top layer is a centred disc.
std::vector<Site> columnsInside(float radius, float spacing, float reach) {
  const double room = radius - reach;  // farthest a granule centre may be from the axis
  std::vector<Site> sites;
  if (room <= 0.0) return sites;
  const auto half = static_cast<std::int32_t>(std::floor(room / spacing));
  for (std::int32_t j = -half; j <= half; ++j) {
    for (std::int32_t i = -half; i <= half; ++i) {
      if (std::hypot(double(i), double(j)) * spacing <= room) sites.push_back({i, j});
    }
  }
  std::sort(sites.begin(), sites.end(), [](const Site& a, const Site& b) {
    const std::int32_t ra = a.i * a.i + a.j * a.j;
    const std::int32_t rb = b.i * b.i + b.j * b.j;
    if (ra != rb) return ra < rb;
    return a.j != b.j ? a.j < b.j : a.i < b.i;
  });
  return sites;
}

// Groups sites into runs of consecutive columns per row.
std::vector<Run> runsOf(std::vector<Site> sites) {
  std::sort(sites.begin(), sites.end(),
            [](const Site& a, const Site& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
  std::vector<Run> runs;
  for (const Site& site : sites) {
    if (runs.empty() || runs.back().row != site.j ||
        runs.back().firstColumn + std::int32_t(runs.back().columns) != site.i) {
      runs.push_back({site.j, site.i, 0});
    }
    ++runs.back().columns;
  }
  return runs;
}

scenes::CylinderPile::Config sceneConfig(const DensePileConfig& config, float wallHeight) {
  scenes::CylinderPile::Config scene;
  scene.particleDiameter = config.particleDiameter;
  scene.batches = 1;
  // One "batch" of one column holds every granule: the scene then sizes the world for exactly
  // this pile (its footprint check passes trivially; the lattice is ours, see DensePile::build).
  scene.batch = {1, config.granules, 1};
  scene.cylinderRadius = config.cylinderRadius;
  scene.cylinderHeight = wallHeight;
  scene.seed = config.seed;
  return scene;
}

}  // namespace

DensePile::DensePile(const DensePileConfig& config) : m_config(config) {
  const float d = config.particleDiameter;
  if (config.granules == 0) {
    throw InvalidArgument("dense pile: granules = 0; must be > 0");
  }
  // The outer radius does not depend on the density; the mass is set once the settings exist.
  m_granuleOuterRadius =
      tetrahedronTemplate(d, WorldSettings{}.material.density).boundingRadius + 0.5f * d;

  const float spacing = config.spacing * d;
  const float jitter = config.jitter * spacing;
  // Horizontally a granule centre moves up to jitter along x and z.
  const float reach = m_granuleOuterRadius + jitter * std::sqrt(2.0f);
  const std::vector<Site> sites = columnsInside(config.cylinderRadius * d, spacing, reach);
  if (sites.empty()) {
    throw InvalidArgument("dense pile: no lattice column of spacing " +
                          std::to_string(config.spacing) + " d fits inside a wall of radius " +
                          std::to_string(config.cylinderRadius) + " d");
  }
  DensePileLayout& layout = m_layout;
  layout.columns = static_cast<std::uint32_t>(sites.size());
  layout.fullLayers = config.granules / layout.columns;
  layout.topLayerGranules = config.granules % layout.columns;
  const std::uint32_t layers = layout.fullLayers + (layout.topLayerGranules > 0 ? 1u : 0u);
  // Floor particles are centred on y = 0 with radius d/2.
  layout.bottomLayerY = 0.5f * d + m_granuleOuterRadius + jitter + kFloorClearance * d;
  layout.columnTop = layout.bottomLayerY + static_cast<float>(layers - 1) * spacing + jitter +
                     m_granuleOuterRadius;
  layout.wallHeight = config.cylinderHeight;
  if (layout.columnTop / d + kWallHeadroom > config.cylinderHeight) {
    layout.wallHeight = 10.0f * std::ceil((layout.columnTop / d + kWallHeadroom) / 10.0f);
    layout.wallRaised = true;
  }
  m_scene = scenes::CylinderPile(sceneConfig(config, layout.wallHeight));
  // Also validates the counts against what a World can index.
  m_granuleMass = tetrahedronTemplate(d, settings().material.density).mass;
}

WorldSettings DensePile::settings() const { return m_scene.settings(); }

void DensePile::build(World& world) const {
  const float d = m_config.particleDiameter;
  const float radius = m_config.cylinderRadius * d;
  // The container of CylinderPile::build: smooth wall, rough particle floor, and a safety plane
  // one diameter under the floor.
  world.addCollider(
      Cylinder{.base = {0.0f, 0.0f, 0.0f}, .radius = radius, .height = m_layout.wallHeight * d});
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d});
  world.addCollider(Plane{.normal = {0.0f, 1.0f, 0.0f}, .offset = -d});

  const float spacing = m_config.spacing * d;
  const float jitter = m_config.jitter * spacing;
  const std::vector<Site> sites =
      columnsInside(radius, spacing, m_granuleOuterRadius + jitter * std::sqrt(2.0f));
  std::uint64_t seed = m_config.seed * 1000003u;
  const auto addRuns = [&](const std::vector<Site>& columns, std::uint32_t firstLayer,
                           std::uint32_t layers) {
    const float centreY = m_layout.bottomLayerY +
                          (static_cast<float>(firstLayer) + 0.5f * float(layers - 1)) * spacing;
    for (const Run& run : runsOf(columns)) {
      const float middle =
          static_cast<float>(run.firstColumn) + 0.5f * static_cast<float>(run.columns - 1);
      world.addGranules(GranuleBlock{.center = {middle * spacing, centreY, run.row * spacing},
                                     .countX = run.columns,
                                     .countY = layers,
                                     .countZ = 1,
                                     .spacing = spacing,
                                     .jitter = m_config.jitter,
                                     .seed = seed++});
    }
  };
  if (m_layout.fullLayers > 0) addRuns(sites, 0, m_layout.fullLayers);
  if (m_layout.topLayerGranules > 0) {
    const std::vector<Site> top(sites.begin(), sites.begin() + m_layout.topLayerGranules);
    addRuns(top, m_layout.fullLayers, 1);
  }
}

}  // namespace sandphys::bench
