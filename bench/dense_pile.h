#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <sandphys/sandphys.h>

#include "bench_pile.h"
#include "scenes/cylinder_pile.h"

namespace sandphys::bench {

/// How the granules of a dense pile start.
enum class Packing {
  /// Randomly oriented granules on a cubic lattice (GranuleBlock) at the smallest spacing that
  /// cannot overlap in any orientation: solid fraction ~0.18, no contacts; the column has to fall
  /// and compact under gravity, which takes far longer than a benchmark can wait for tall piles.
  Lattice,
  /// Granules all in one orientation on a cubic lattice of spacing √2 d, turned 45° about y: their
  /// particles form a face-centred cubic sphere packing that continues the rough floor's square
  /// lattice, every sphere touching 12 others (solid fraction 0.74), the layers pressed together
  /// by the weight they carry. Static from the first substep, but denser and more ordered than a
  /// poured pile: an upper bound on neighbours per particle where Lattice is a lower one.
  Crystal,
};

/// "lattice" or "crystal".
std::string_view packingName(Packing packing);

/// How to build the benchmark pile directly, without pouring batches: the cylinder pile scene's
/// container (smooth wall, rough particle floor, safety plane) filled from just above the floor.
struct DensePileConfig {
  /// Granules in the pile; > 0.
  std::uint32_t granules = 4096;
  Packing packing = Packing::Crystal;
  /// Particle diameter d, m.
  float particleDiameter = 0.02f;
  /// Radius of the cylinder wall and of the rough floor, d (the paper: 50 d).
  float cylinderRadius = 50.0f;
  /// Height of the cylinder wall, d (the paper: 100 d). Raised when the initial column is taller
  /// (see PileLayout::wallRaised).
  float cylinderHeight = 100.0f;
  /// Lattice packing: spacing, d. With jitter it must satisfy spacing · (1 - 2 jitter) >= 2.225 d
  /// (the room a granule needs in any orientation, see GranuleBlock::spacing).
  float spacing = 2.25f;
  /// Lattice packing: random offset per axis, in units of the spacing; [0, 0.25].
  float jitter = 0.005f;
  /// Lattice packing: seed of the jitter and orientations (same seed, same pile).
  std::uint64_t seed = 1;
  /// The contact law the pile is simulated with.
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
};

/// The pile of `config`: its layout, the scene whose container and sizing it reuses, and the
/// settings of a World that holds exactly it.
class DensePile final : public BenchPile {
 public:
  /// Throws InvalidArgument when no lattice column fits inside the wall or the granules do not
  /// fit a World.
  explicit DensePile(const DensePileConfig& config);

  const DensePileConfig& config() const { return m_config; }
  const PileLayout& layout() const override { return m_layout; }
  /// The cylinder pile scene with this pile's geometry; used for its settings, container test
  /// and pile-top measure (its build() is never called: it would drop a batch).
  const scenes::CylinderPile& scene() const { return m_scene; }

  /// Settings of the scene (material, diameter) with capacities for the floor and every granule.
  WorldSettings settings() const override;
  /// Adds the container of CylinderPile::build and the granules to an empty `world` made from
  /// settings(). Crystal packing poses every granule with World::setBodyState (a small sync per
  /// granule: seconds for 256K granules).
  void build(World& world) const override;

  std::uint32_t granules() const override { return m_config.granules; }
  float particleDiameter() const override { return m_config.particleDiameter; }
  /// Mass of one granule, kg, and the distance of its outermost particle surface from its
  /// centre, m.
  float granuleMass() const override { return m_granuleMass; }
  float granuleOuterRadius() const { return m_granuleOuterRadius; }
  /// CylinderPile::pileTop plus the granule's outer radius (the scene is never built, so its
  /// own pileTop measures centre heights).
  float pileTop(std::span<const BodyState> bodies) const override;
  /// CylinderPile::contains: within the wall's radius and not below the floor.
  bool contains(const Vec3& centre) const override { return m_scene.contains(centre); }
  /// The cylinder from one diameter below the floor to the initial column's top.
  scenes::SceneBounds bounds() const override;

 private:
  void addLattice(World& world) const;
  void addCrystal(World& world) const;

  DensePileConfig m_config;
  PileLayout m_layout;
  scenes::CylinderPile m_scene;
  float m_granuleMass = 0.0f;
  float m_granuleOuterRadius = 0.0f;
};

}  // namespace sandphys::bench
