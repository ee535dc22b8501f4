#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// The benchmark of Longmore et al. 2013, section 5 (Fig. 10): granules poured in batches into a
/// smooth cylinder wall of radius 50 d and height 100 d standing on a rough (particle) floor.
/// The first batch starts 50 d above the floor; each next batch is dropped 15 d above the top of
/// the pile once the previous one has settled.
///
/// A batch keeps the paper's count (32 × 32 × 16 = 16,384 granules) but not its square shape:
/// the paper spaced grains about 2 d apart, while our granules may not start overlapping, which
/// needs about 2.4 d (kDefaultGranuleSpacing), and a 32 × 32 square at 2.4 d would reach 52.6 d
/// from the axis, outside the wall. So the X·Z columns of a batch are the lattice columns nearest
/// the axis (a disc of radius ~43 d), each Y granules high.
class CylinderPile final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Number of batches dropped in total; >= 1.
    std::uint32_t batches = 1;
    /// Granules per batch: X·Z columns (arranged as a disc, see above) of Y layers. The paper's
    /// 32×32×16 batch is 32 × 32 granules across and 16 layers high.
    Count3 batch{32, 16, 32};
    /// Lattice spacing of a batch, d; with GranuleBlock's jitter it must leave room for any
    /// orientation (see GranuleBlock::spacing).
    float spacing = kDefaultGranuleSpacing;
    /// Radius of the cylinder wall and of the rough floor disc, d.
    float cylinderRadius = 50.0f;
    /// Height of the cylinder wall, d.
    float cylinderHeight = 100.0f;
    /// Height of the first batch's lowest layer above the floor, d.
    float firstDropHeight = 50.0f;
    /// Gap between the top of the pile and the next batch's lowest layer, d.
    float dropGap = 15.0f;
    /// A batch has settled when the world's kinetic energy per granule of that batch is below
    /// ½ m v² for this speed v, m/s.
    float settleSpeed = 0.05f;
    /// A batch that has not settled after this long is followed by the next anyway, s.
    float maxSecondsPerBatch = 5.0f;
    /// Seed of the batches' jitter and orientations: same seed, same pile.
    std::uint64_t seed = 1;
  };

  /// Makes the scene with the paper's parameters.
  CylinderPile() = default;
  /// Makes the scene with `config`.
  explicit CylinderPile(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "cylinder-pile".
  std::string_view name() const override { return "cylinder-pile"; }
  /// Capacity for every batch plus the floor, allocated up front as in the paper.
  WorldSettings worldSettings() const override;
  /// Cylinder wall, rough floor, a safety-net plane below it and the first batch.
  void build(World& world) override;
  /// Drops the next batch once the newest has settled (one World::readBodies per batch).
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once the last batch has settled.
  bool finished() const override { return m_finished; }
  /// "batch i/n", plus "settled" at the end.
  std::string status() const override;
  /// Within the wall's radius and not below the floor.
  bool contains(const Vec3& centre) const override;
  /// Batches dropped and settled, mean settle time, pile top (m and d), cylinder size.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// Every field of Config, by kebab-case name (see --list of sandphys-samples).
  std::vector<SceneParameter> parameters() override;
  /// The cylinder, from just below the floor to the top of the wall.
  SceneBounds bounds() const override;

  /// Granules in one batch.
  std::uint32_t batchGranules() const;
  /// Largest distance of a granule's particle from the axis when a batch is dropped, m (lattice,
  /// jitter and granule size). settings() refuses a batch whose footprint leaves the cylinder.
  float batchReach() const;
  /// Batches added to the world so far.
  std::uint32_t batchesDropped() const { return m_batchesDropped; }
  /// Top of the pile (m) when the last batch was dropped; the floor before the first.
  float lastPileTop() const { return m_pileTop; }
  /// Simulated time (s) each batch took to settle or to reach maxSecondsPerBatch.
  const std::vector<double>& settleTimes() const { return m_settleTimes; }

  /// Height (m) of the top surface of the granules in `bodies` that are inside the container
  /// (pileSurface with the granule's outer radius), so that a few bouncing granules do not lift
  /// the next batch; 0 when there are none.
  float pileTop(std::span<const BodyState> bodies) const;

 private:
  /// One lattice row of a batch's footprint: columns firstColumn..firstColumn + columns - 1 at
  /// z = row (in units of the spacing).
  struct FootprintRow {
    std::int32_t row = 0;
    std::int32_t firstColumn = 0;
    std::uint32_t columns = 0;
  };
  std::vector<FootprintRow> footprint() const;
  void dropBatch(World& world, float bottomLayerY, double simTime);
  float d() const { return m_config.particleDiameter; }

  Config m_config;
  std::uint32_t m_batchesDropped = 0;
  double m_lastDropTime = 0.0;
  // Simulated time the newest batch needs to fall onto the pile before it can have settled: a
  // batch dropped from rest starts with no kinetic energy, so "calm" means nothing before then.
  double m_minSettleTime = 0.0;
  float m_pileTop = 0.0f;
  float m_granuleMass = 0.0f;
  float m_granuleOuterRadius = 0.0f;
  std::vector<double> m_settleTimes;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
