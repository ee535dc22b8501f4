#include "box_pile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scenes/kit/checks.h"
#include "scenes/kit/course.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::bench {

namespace {

// Gap between the box's walls (and floor) and the nearest particle surface a granule can reach at
// the start, d: granules start clear of every wall, so that none starts pushed by one.
constexpr float kWallClearance = 0.05f;
// Room kept between the initial column's top and the box's lid, d (then rounded up to 10 d): the
// box is closed, and the column's top must fall freely.
constexpr float kLidHeadroom = 5.0f;
// Default settling, in free-fall times of the initial column's top onto the floor (see
// boxPileSettleSteps).
constexpr double kSettleFalls = 1.5;

// A lattice column of the box pile, by its lattice indices along x (i) and z (j), 0..n-1.
struct Site {
  std::int32_t i = 0;
  std::int32_t j = 0;
};

// The layout of `config` and the lattice columns per side of the box; throws InvalidArgument
// when no column fits.
PileLayout layoutOf(const BoxPileConfig& config, std::uint32_t& columnsPerSide) {
  const double d = config.particleDiameter;
  if (config.granules == 0) throw InvalidArgument("box pile: granules = 0; must be > 0");
  const double side = boxPileSide(config) * d;
  const double spacing = double(config.spacing) * d;
  const double jitter = double(config.jitter) * spacing;  // per axis, m
  // How far a granule's particles may reach from its lattice site, m.
  const double reach = kGranuleReach * d + jitter + kWallClearance * d;
  const double room = side - 2.0 * reach;  // span of the lattice sites along x and z
  if (room < 0.0) {
    const double fewest = std::ceil(4096.0 * std::pow(2.0 * reach / d / config.sideAt4096, 2.0));
    throw InvalidArgument("box pile: " + std::to_string(config.granules) +
                          " granules make a box of side " + scenes::kit::numberText(side / d) +
                          " d, too narrow for one granule (" +
                          scenes::kit::numberText(2.0 * reach / d) + " d); use at least " +
                          scenes::kit::numberText(fewest) + " granules");
  }
  columnsPerSide = static_cast<std::uint32_t>(std::floor(room / spacing)) + 1u;
  PileLayout layout;
  layout.spacing = static_cast<float>(spacing);
  layout.columns = columnsPerSide * columnsPerSide;
  layout.fullLayers = config.granules / layout.columns;
  layout.topLayerGranules = config.granules % layout.columns;
  const std::uint32_t layers = layout.fullLayers + (layout.topLayerGranules > 0 ? 1u : 0u);
  const double bottom = reach;  // the floor is the box's bottom face, y = 0
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    layout.layerY.push_back(static_cast<float>(bottom + double(layer) * spacing));
  }
  layout.columnTop = static_cast<float>(layout.layerY.back() + reach - kWallClearance * d);
  layout.wallHeight =
      10.0f * std::ceil((layout.columnTop / config.particleDiameter + kLidHeadroom) / 10.0f);
  layout.wallRaised = false;
  layout.boxSide = static_cast<float>(side / d);
  return layout;
}

// The `count` columns nearest the box's axis (ties by row, then column): a partial top layer
// spreads over the middle of the pile rather than along one wall.
std::vector<Site> centralSites(std::uint32_t columnsPerSide, std::uint32_t count) {
  std::vector<Site> sites;
  for (std::uint32_t j = 0; j < columnsPerSide; ++j) {
    for (std::uint32_t i = 0; i < columnsPerSide; ++i) {
      sites.push_back({std::int32_t(i), std::int32_t(j)});
    }
  }
  // Twice the distance from the axis, so that it stays an integer.
  const auto ring = [&](const Site& s) {
    const std::int64_t x = 2 * std::int64_t(s.i) - (std::int64_t(columnsPerSide) - 1);
    const std::int64_t z = 2 * std::int64_t(s.j) - (std::int64_t(columnsPerSide) - 1);
    return x * x + z * z;
  };
  std::sort(sites.begin(), sites.end(), [&](const Site& a, const Site& b) {
    if (ring(a) != ring(b)) return ring(a) < ring(b);
    return a.j != b.j ? a.j < b.j : a.i < b.i;
  });
  sites.resize(count);
  // Row by row, as the full layers' block orders its bodies.
  std::sort(sites.begin(), sites.end(),
            [](const Site& a, const Site& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
  return sites;
}

}  // namespace

double boxPileSide(const BoxPileConfig& config) {
  return double(config.sideAt4096) * std::sqrt(double(config.granules) / 4096.0);
}

std::uint32_t boxPileSettleSteps(const BoxPileConfig& config) {
  std::uint32_t columnsPerSide = 0;
  const PileLayout layout = layoutOf(config, columnsPerSide);
  // BoxPile keeps WorldSettings' default gravity.
  const double g = scenes::kit::kGravity;
  const double seconds = kSettleFalls * scenes::kit::fallTime(layout.columnTop, 0.0, g);
  return static_cast<std::uint32_t>(std::ceil(seconds / config.timeStep));
}

BoxPile::BoxPile(const BoxPileConfig& config) : m_config(config) {
  m_layout = layoutOf(config, m_columnsPerSide);
  m_granuleOuterRadius = static_cast<float>(kGranuleReach * config.particleDiameter);
  if (std::uint64_t(config.granules) * 4u > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("box pile: " + std::to_string(config.granules) +
                          " granules need more particles than a World can index");
  }
  // The World would refuse these settings only after compiling its kernels; say it now, as a
  // property of the benchmark's fixed time step.
  const WorldSettings s = settings();
  try {
    static_cast<void>(ContactModel::fromSettings(s));
  } catch (const InvalidArgument& error) {
    throw InvalidArgument(
        std::string("box pile (fixed time step ") + scenes::kit::numberText(config.timeStep) +
        " s, E " + scenes::kit::numberText(config.material.youngsModulus) + " Pa, speed guard " +
        scenes::kit::numberText(s.maxSpeed) + " m/s): the World refuses it: " + error.what());
  }
  m_granuleMass = tetrahedronTemplate(config.particleDiameter, config.material.density).mass;
}

WorldSettings BoxPile::settings() const {
  WorldSettings s;
  s.particleDiameter = m_config.particleDiameter;
  s.material = m_config.material;
  s.contactLaw = m_config.contactLaw;
  s.timeStep = m_config.timeStep;
  // The fastest a granule gets is the fall of the column's top onto the floor (with the margin of
  // the pouring scenes); t_n, and so the stiffness check of the fixed time step, is taken there.
  s.maxSpeed = scenes::kit::pourGuardSpeed(0.0f, m_layout.columnTop, length(s.gravity));
  s.maxBodies = m_config.granules;
  s.maxParticles = 4u * m_config.granules;
  return s;
}

void BoxPile::build(World& world) const {
  const float d = m_config.particleDiameter;
  const float side = m_layout.boxSide * d;
  const float height = m_layout.wallHeight * d;
  // One closed container: its bottom face is the floor, its four sides the walls, its top a lid
  // the column never reaches.
  world.addCollider(Box{.center = {0.0f, 0.5f * height, 0.0f},
                        .halfExtents = {0.5f * side, 0.5f * height, 0.5f * side},
                        .inside = true,
                        .material = m_config.wallMaterial});

  const float spacing = m_layout.spacing;
  const auto n = static_cast<float>(m_columnsPerSide);
  const float half = 0.5f * (n - 1.0f);  // lattice index of the box's axis
  std::uint64_t seed = m_config.seed * 1000003u;
  if (m_layout.fullLayers > 0) {
    const float centreY =
        m_layout.layerY[0] + 0.5f * static_cast<float>(m_layout.fullLayers - 1) * spacing;
    world.addGranules(GranuleBlock{.center = {0.0f, centreY, 0.0f},
                                   .countX = m_columnsPerSide,
                                   .countY = m_layout.fullLayers,
                                   .countZ = m_columnsPerSide,
                                   .spacing = spacing,
                                   .jitter = m_config.jitter,
                                   .seed = seed++});
  }
  if (m_layout.topLayerGranules == 0) return;
  // The partial top layer: one GranuleBlock per run of consecutive columns in a row.
  const float y = m_layout.layerY[m_layout.fullLayers];
  const std::vector<Site> sites = centralSites(m_columnsPerSide, m_layout.topLayerGranules);
  for (std::size_t first = 0; first < sites.size();) {
    std::size_t last = first;
    while (last + 1 < sites.size() && sites[last + 1].j == sites[first].j &&
           sites[last + 1].i == sites[last].i + 1) {
      ++last;
    }
    const auto count = static_cast<std::uint32_t>(last - first + 1);
    const float middle = static_cast<float>(sites[first].i) + 0.5f * static_cast<float>(count - 1);
    world.addGranules(
        GranuleBlock{.center = {(middle - half) * spacing, y,
                                (static_cast<float>(sites[first].j) - half) * spacing},
                     .countX = count,
                     .countY = 1,
                     .countZ = 1,
                     .spacing = spacing,
                     .jitter = m_config.jitter,
                     .seed = seed++});
    first = last + 1;
  }
}

float BoxPile::pileTop(std::span<const BodyState> bodies) const {
  return scenes::kit::pileSurface(
      bodies, [this](const Vec3& centre) { return contains(centre); }, m_granuleOuterRadius);
}

bool BoxPile::contains(const Vec3& centre) const {
  const float d = m_config.particleDiameter;
  const float half = 0.5f * m_layout.boxSide * d;
  return std::abs(centre.x) <= half && std::abs(centre.z) <= half && centre.y >= 0.0f &&
         centre.y <= m_layout.wallHeight * d;
}

scenes::SceneBounds BoxPile::bounds() const {
  const float half = 0.5f * m_layout.boxSide * m_config.particleDiameter;
  return {{-half, 0.0f, -half}, {half, m_layout.columnTop, half}};
}

}  // namespace sandphys::bench
