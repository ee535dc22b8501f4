#include "dense_pile.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "scenes/kit/geometry.h"

namespace sandphys::bench {

namespace {

// A lattice column of the pile, by its lattice indices.
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

// Lattice packing: gap between the floor particles' tops and the lowest granule surface, d.
constexpr float kFloorClearance = 0.05f;
// Lattice packing: room kept above the initial column, whose granules bounce as the column
// compacts, when the wall has to be raised, d (then rounded up to 10 d).
constexpr float kWallHeadroom = 5.0f;

// Columns whose granules stay inside the wall (`reach` m from their centre), nearest the axis
// first (ties by row, then column), so that a partial top layer is a centred disc.
std::vector<Site> columnsInside(double radius, double spacing, double reach) {
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

// The sites of layer `layer` of a layout: every column, except in the partial top layer.
std::vector<Site> layerSites(const std::vector<Site>& sites, const PileLayout& layout,
                             std::uint32_t layer) {
  if (layer < layout.fullLayers) return sites;
  return {sites.begin(), sites.begin() + layout.topLayerGranules};
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

// Particle centres of a granule in the template's own frame (tetrahedronTemplate: alternate
// corners of a cube of side d/√2), m.
std::vector<Vec3> granuleCorners(float d) {
  const float h = d / (2.0f * std::numbers::sqrt2_v<float>);
  return {{h, h, h}, {h, -h, -h}, {-h, h, -h}, {-h, -h, h}};
}

// Crystal packing: every granule turned 45° about y. In the template's frame the particle
// centres lie in two layers d/√2 apart (y = ±d/(2√2)), and the granules of a cubic lattice of
// spacing √2 d fill each such layer as a square lattice of spacing d, diagonal to the cube axes.
// Turned by 45° those layers line up with the rough floor's lattice (spacing d along x and z), so
// the lowest layer sits in the floor's hollows: the floor continues the FCC packing downwards.
const Quat kCrystalOrientation{0.92387953f, 0.0f, 0.38268343f, 0.0f};

// Horizontal position (x, z) of crystal column (i, j), m: the lattice vectors √2 d (1, 0) and
// √2 d (0, 1) turned by 45° are d (1, -1) and d (1, 1); the offset puts the lowest particles of
// every granule on the floor's hollows (points ((m + ½) d, (n + ½) d)).
Vec3 crystalColumn(std::int32_t i, std::int32_t j, float d) {
  const Vec3 low = rotate(kCrystalOrientation, granuleCorners(d)[1]);  // a corner at y = -h
  const double x = 0.5 * d - low.x + (double(i) + double(j)) * d;
  const double z = 0.5 * d - low.z + (double(j) - double(i)) * d;
  return {static_cast<float>(x), 0.0f, static_cast<float>(z)};
}

// Crystal columns whose granules stay inside the wall, nearest the axis first.
std::vector<Site> crystalColumnsInside(double radius, float d, double reach) {
  const double room = radius - reach;
  std::vector<Site> sites;
  if (room <= 0.0) return sites;
  const auto half = static_cast<std::int32_t>(std::ceil(room / (std::numbers::sqrt2 * d))) + 1;
  std::vector<std::pair<double, Site>> ranked;
  for (std::int32_t j = -half; j <= half; ++j) {
    for (std::int32_t i = -half; i <= half; ++i) {
      const Vec3 p = crystalColumn(i, j, d);
      const double r = std::hypot(double(p.x), double(p.z));
      if (r <= room) ranked.push_back({r, Site{i, j}});
    }
  }
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    return a.second.j != b.second.j ? a.second.j < b.second.j : a.second.i < b.second.i;
  });
  for (const auto& entry : ranked) sites.push_back(entry.second);
  return sites;
}

scenes::CylinderPile::Config sceneConfig(const DensePileConfig& config, float wallHeight) {
  scenes::CylinderPile::Config scene;
  scene.particleDiameter = config.particleDiameter;
  scene.batches = 1;
  // One "batch" of one column holds every granule: the scene then sizes the world for exactly
  // this pile (its footprint check passes trivially; the layout is ours, see DensePile::build).
  scene.batch = {1, config.granules, 1};
  scene.cylinderRadius = config.cylinderRadius;
  scene.cylinderHeight = wallHeight;
  scene.seed = config.seed;
  return scene;
}

// The pile is built as one column of every granule (sceneConfig), whose own height the scene
// would take for a drop and set a speed guard (and an auto Young's modulus) for a fall that no
// granule makes. The benchmark times the scene's pile: it takes the guard and material of the
// scene's default pour instead.
WorldSettings withThePoursGuard(const DensePileConfig& config, WorldSettings settings) {
  scenes::CylinderPile::Config pour;
  pour.particleDiameter = config.particleDiameter;
  const WorldSettings poured = scenes::CylinderPile(pour).settings();
  settings.maxSpeed = poured.maxSpeed;
  settings.material.youngsModulus = poured.material.youngsModulus;
  return settings;
}

// Centre heights (m) of the crystal's layers, in static equilibrium: the lowest particles sit in
// the floor's hollows and every layer rests on the one below with the Hertz overlap of its load.
// Each granule's two lowest particles touch four particles below at 45° from the vertical, so a
// column of granules (one per layer, 2 d² of floor) carrying `load` newtons presses each of
// these 8 contacts with load / (8 cos 45°). Starting at this overlap (0.04 d under 70 layers for
// the default material, summing to several d over a tall pile) instead of just touching spares
// the column a free fall and an elastic wave that take hundreds of milliseconds to die down.
std::vector<float> crystalLayerHeights(const DensePileConfig& config, const PileLayout& layout) {
  const double d = config.particleDiameter;
  const WorldSettings settings = withThePoursGuard(
      config, scenes::CylinderPile(sceneConfig(config, config.cylinderHeight)).settings());
  const double stiffness = ContactModel::fromSettings(settings).stiffnessGrain;
  const Vec3 g = settings.gravity;
  const double weight =
      tetrahedronTemplate(config.particleDiameter, settings.material.density).mass *
      std::sqrt(double(g.x) * g.x + double(g.y) * g.y + double(g.z) * g.z);
  const std::uint32_t layers = layout.fullLayers + (layout.topLayerGranules > 0 ? 1u : 0u);
  // Weight of the layers from `layer` up, per column: a partial top layer is spread evenly.
  const auto columnLoad = [&](std::uint32_t layer) {
    const double full = layout.fullLayers > layer ? layout.fullLayers - layer : 0.0;
    return weight * (full + double(layout.topLayerGranules) / layout.columns);
  };
  // Vertical distance between the centres of two touching particles d/√2 apart horizontally,
  // pressed together by a contact force `force`.
  const auto verticalGap = [&](double force) {
    const double distance = d - hertzRestingOverlap(force, stiffness);
    return std::sqrt(std::max(distance * distance - 0.5 * d * d, 0.0));
  };
  const double h = d / (2.0 * std::numbers::sqrt2);  // particle layers of a granule at ±h
  std::vector<float> heights;
  double y = 0.0;  // centre of the floor particles
  double top = 0.0;
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    const double force = columnLoad(layer) / (8.0 * std::numbers::sqrt2 / 2.0);
    y = (layer == 0 ? 0.0 : top) + verticalGap(force) + h;
    top = y + h;
    heights.push_back(static_cast<float>(y));
  }
  return heights;
}

}  // namespace

std::string_view packingName(Packing packing) {
  return packing == Packing::Crystal ? "crystal" : "lattice";
}

DensePile::DensePile(const DensePileConfig& config) : m_config(config) {
  const float d = config.particleDiameter;
  if (config.granules == 0) {
    throw InvalidArgument("dense pile: granules = 0; must be > 0");
  }
  // The outer radius does not depend on the density; the mass is set once the settings exist.
  m_granuleOuterRadius =
      tetrahedronTemplate(d, WorldSettings{}.material.density).boundingRadius + 0.5f * d;
  const float radius = config.cylinderRadius * d;
  const bool crystal = config.packing == Packing::Crystal;

  PileLayout& layout = m_layout;
  // Crystal: the unloaded layer spacing (the layers are pressed closer, see below); within a
  // layer the columns are exactly √2 d apart.
  layout.spacing = crystal ? static_cast<float>(std::numbers::sqrt2 * d) : config.spacing * d;
  const float jitter = crystal ? 0.0f : config.jitter * layout.spacing;
  // Horizontally a granule centre moves up to `jitter` along x and along z.
  const std::vector<Site> sites =
      crystal
          ? crystalColumnsInside(radius, d, m_granuleOuterRadius)
          : columnsInside(radius, layout.spacing, m_granuleOuterRadius + jitter * std::sqrt(2.0f));
  if (sites.empty()) {
    throw InvalidArgument("dense pile: no lattice column of spacing " +
                          std::to_string(layout.spacing / d) + " d fits inside a wall of radius " +
                          std::to_string(config.cylinderRadius) + " d");
  }
  layout.columns = static_cast<std::uint32_t>(sites.size());
  layout.fullLayers = config.granules / layout.columns;
  layout.topLayerGranules = config.granules % layout.columns;
  const std::uint32_t layers = layout.fullLayers + (layout.topLayerGranules > 0 ? 1u : 0u);
  if (crystal) {
    layout.layerY = crystalLayerHeights(config, layout);
  } else {
    // Floor particles are centred on y = 0 with radius d/2.
    const float bottom = 0.5f * d + m_granuleOuterRadius + jitter + kFloorClearance * d;
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
      layout.layerY.push_back(bottom + static_cast<float>(layer) * layout.spacing);
    }
  }
  layout.columnTop = layout.layerY.back() + jitter + m_granuleOuterRadius;
  layout.wallHeight = config.cylinderHeight;
  const float headroom = crystal ? 0.0f : kWallHeadroom;  // a crystal hardly moves
  if (layout.columnTop / d + headroom > config.cylinderHeight) {
    layout.wallHeight = 10.0f * std::ceil((layout.columnTop / d + headroom) / 10.0f);
    layout.wallRaised = true;
  }
  m_scene = scenes::CylinderPile(sceneConfig(config, layout.wallHeight));
  m_scene.setContactLaw(config.contactLaw);
  // Also validates the counts against what a World can index.
  m_granuleMass = tetrahedronTemplate(d, settings().material.density).mass;
}

WorldSettings DensePile::settings() const {
  return withThePoursGuard(m_config, m_scene.settings());
}

float DensePile::pileTop(std::span<const BodyState> bodies) const {
  return m_scene.pileTop(bodies) + m_granuleOuterRadius;
}

scenes::SceneBounds DensePile::bounds() const {
  const float d = m_config.particleDiameter;
  const float r = m_config.cylinderRadius * d;
  return {{-r, -d, -r}, {r, m_layout.columnTop, r}};
}

void DensePile::build(World& world) const {
  const float d = m_config.particleDiameter;
  // The container of CylinderPile::build.
  scenes::kit::addCylinderContainer(world, m_config.cylinderRadius * d, m_layout.wallHeight * d, d);
  if (m_config.packing == Packing::Crystal) {
    addCrystal(world);
  } else {
    addLattice(world);
  }
}

void DensePile::addLattice(World& world) const {
  const float d = m_config.particleDiameter;
  const float spacing = m_layout.spacing;
  const float jitter = m_config.jitter * spacing;
  const std::vector<Site> sites = columnsInside(m_config.cylinderRadius * d, spacing,
                                                m_granuleOuterRadius + jitter * std::sqrt(2.0f));
  std::uint64_t seed = m_config.seed * 1000003u;
  // One GranuleBlock per row run covers all full layers; the partial top layer gets its own.
  const auto addRuns = [&](const std::vector<Site>& columns, std::uint32_t firstLayer,
                           std::uint32_t layers) {
    const float centreY =
        m_layout.layerY[firstLayer] + 0.5f * static_cast<float>(layers - 1) * spacing;
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
    addRuns(layerSites(sites, m_layout, m_layout.fullLayers), m_layout.fullLayers, 1);
  }
}

void DensePile::addCrystal(World& world) const {
  const float d = m_config.particleDiameter;
  const std::vector<Site> sites =
      crystalColumnsInside(m_config.cylinderRadius * d, d, m_granuleOuterRadius);
  const std::uint32_t layers = m_layout.fullLayers + (m_layout.topLayerGranules > 0 ? 1u : 0u);
  std::vector<BodyDesc> poses;
  poses.reserve(m_config.granules);
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    std::vector<Site> layerOrder = layerSites(sites, m_layout, layer);
    // Row by row, as the lattice packing orders its bodies (memory locality is part of the cost).
    std::sort(layerOrder.begin(), layerOrder.end(),
              [](const Site& a, const Site& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
    const float y = m_layout.layerY[layer];
    for (const Site& site : layerOrder) {
      const Vec3 column = crystalColumn(site.i, site.j, d);
      poses.push_back({.position = {column.x, y, column.z}, .orientation = kCrystalOrientation});
    }
  }
  world.addGranules(poses);
}

}  // namespace sandphys::bench
