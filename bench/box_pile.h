#pragma once

#include <cstdint>
#include <span>

#include <sandphys/sandphys.h>

#include "bench_pile.h"

namespace sandphys::bench {

/// The box pile that DEM codes are commonly timed on: tetrahedral granules in a closed square
/// box of flat walls with friction, the box's bottom face the floor (no rough particle floor),
/// settled from a loose random lattice. The footprint grows with the granule count so that the
/// settled pile is about 15 d high at every size.
struct BoxPileConfig {
  /// Granules in the pile; > 0 (and enough for one lattice column to fit the box).
  std::uint32_t granules = 4096;
  /// Particle diameter d, m.
  float particleDiameter = 0.01f;
  /// Inner side of the box for 4096 granules, d; the side scales as sqrt(granules / 4096), so
  /// that every size settles to the same height (about 15 d for 36 d).
  float sideAt4096 = 36.0f;
  /// The grains: 2500 kg/m³, E = 1e7 Pa, ν = 0.3, e = 0.5, μ = 0.5.
  Material material{.density = 2500.0f,
                    .youngsModulus = 1.0e7f,
                    .poissonRatio = 0.3f,
                    .restitution = 0.5f,
                    .friction = 0.5f};
  /// The box's walls and floor: the same μ and e as between grains.
  SurfaceMaterial wallMaterial{.friction = 0.5f, .restitution = 0.5f};
  /// Fixed substep, s; > 0. A World refuses one above t_n / kMinStepsPerContact at the speed
  /// guard (BoxPile's constructor checks it first and says so).
  float timeStep = 5.0e-5f;
  /// Lattice spacing, d. With jitter it must satisfy spacing · (1 - 2 jitter) >= 2.225 d (the
  /// room a granule needs in any orientation, see GranuleBlock::spacing).
  float spacing = 2.25f;
  /// Random offset per axis, in units of the spacing; [0, 0.25].
  float jitter = 0.005f;
  /// Seed of the jitter and orientations (same seed, same pile).
  std::uint64_t seed = 1;
  /// The contact law the pile is simulated with.
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
};

/// Inner side of the box of `config`, d: sideAt4096 · sqrt(granules / 4096).
double boxPileSide(const BoxPileConfig& config);

/// Substeps the box pile settles by default before it is timed: 1.5 times the free fall of the
/// initial column's top onto the floor (the last granule to land falls almost that far), which
/// leaves about half as long again for the impacts to die down.
std::uint32_t boxPileSettleSteps(const BoxPileConfig& config);

/// The pile of `config`: a lattice of randomly oriented granules (GranuleBlock) centred in the
/// box, filled layer by layer from just above the floor; a partial top layer takes the columns
/// nearest the box's axis. The column is about 2.5 times as tall as the settled pile and has to
/// fall and compact before it is timed.
class BoxPile final : public BenchPile {
 public:
  /// Throws InvalidArgument when no lattice column fits the box, the granules do not fit a World,
  /// or the World would refuse the settings (the fixed time step above the stiffness limit: the
  /// message names the time step and the limit).
  explicit BoxPile(const BoxPileConfig& config);

  const BoxPileConfig& config() const { return m_config; }
  const PileLayout& layout() const override { return m_layout; }

  /// Diameter, material, fixed time step, a speed guard for the fall of the column's top onto
  /// the floor, and capacities for exactly the granules.
  WorldSettings settings() const override;
  /// Adds the box (one container collider, `.inside = true`) and the granules.
  void build(World& world) const override;

  std::uint32_t granules() const override { return m_config.granules; }
  float particleDiameter() const override { return m_config.particleDiameter; }
  float granuleMass() const override { return m_granuleMass; }
  float pileTop(std::span<const BodyState> bodies) const override;
  /// Inside the box's footprint and between its floor and lid.
  bool contains(const Vec3& centre) const override;
  /// The box from its floor to the initial column's top.
  scenes::SceneBounds bounds() const override;

 private:
  BoxPileConfig m_config;
  PileLayout m_layout;
  /// Lattice columns along x and along z.
  std::uint32_t m_columnsPerSide = 0;
  float m_granuleMass = 0.0f;
  float m_granuleOuterRadius = 0.0f;
};

}  // namespace sandphys::bench
