#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/analysis/heap.h>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// The angle of repose as the paper measures it (Longmore et al. 2013, section 6.1.4, Fig. 15):
/// a reservoir of settled sand stands on a ledge above a sump; a scupper, a slot across the
/// whole depth of the container at the foot of the reservoir's wall, opens, and sand runs out
/// and down into the sump. The pile in the sump builds up against the ledge until it buries the
/// scupper and the flow stops; its flank, fed by avalanches from the slot (an injection, in the
/// paper's words), stands at the angle of repose, which comes from a robust line through its
/// surface granules (sandphys::analysis::angleOfRepose with HeapShape::ridge).
///
/// Geometry (y up; the slot runs along z, the sand flows toward +x): the sump's floor is a rough
/// floor (static particles, centres at y = 0) from x = 0, the ledge's face, to x = sumpLength d,
/// `depth` d across in z between the side walls of one box that holds everything. The ledge is a
/// solid block under the reservoir whose top, ledge d high, is the reservoir's floor; the
/// reservoir is reservoirWidth d wide in x, between the box's end wall and the gate, a wall that
/// stands on the ledge flush with the ledge's face. At the release the gate rises by `outlet` d,
/// which opens the scupper. Sand that runs off the sump's far end falls into a sink: the sump's
/// pile keeps its length at most.
///
/// Where it differs from the paper, and why:
/// - The paper's container is 100 d deep and holds 64 K granules, of which about 24 K pass into
///   the sump before the scupper is closed. Here the scupper stays open: the pile in the sump
///   closes it. The defaults are 1200 granules in a container 16 d deep, so the two side walls
///   are close and hold the pile up a little; the flank is read away from them (wallMargin).
/// - The walls' friction is fixed at 0.5 whatever the grains' μ, as for the paper's Fig. 22;
///   the sump's floor is made of particles, whose friction is the grains' μ (its roughness holds
///   the pile's foot whatever μ is).
///   A narrow reservoir (12 d) keeps little sand behind the slot, so that a small fill is enough
///   to bury it: a sump pile 12 d high at μ = 0.1 takes about a thousand granules.
/// - The scupper is 10 d high: lower slots jam (at μ = 0.5 a 4 d slot let 34 granules through).
/// - The reservoir is filled as the hourglass is: granules on a loose lattice (10.7 d³ each),
///   which collapses to about a third of its height (3.6 d³ each) and settles before the gate
///   opens.
/// - The softer material of the hourglass scene (Young's modulus 2e6 Pa): a run takes seconds.
class ReposeScupper final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Granules in the reservoir; >= 1.
    std::uint32_t granules = 1200;
    /// Coulomb friction coefficient μ of the grains (and of the sump floor's particles).
    float friction = 0.5f;
    /// Coulomb friction coefficient of the walls, the ledge and the gate; the paper fixes it at
    /// 0.5 for its angle of repose against μ (Fig. 22).
    float wallFriction = 0.5f;
    /// Height of the scupper once the gate has risen, d: the "outlet".
    float outlet = 10.0f;
    /// Depth of the container across the slot (z), d.
    float depth = 16.0f;
    /// Width of the reservoir's inside (x), d.
    float reservoirWidth = 12.0f;
    /// Height of the ledge (the reservoir's floor) above the sump's floor, d.
    float ledge = 12.0f;
    /// Length of the sump's floor from the ledge's face (x), d.
    float sumpLength = 40.0f;
    /// The flank is read from surface cells at least this far from the side walls, d.
    float wallMargin = 3.0f;
    /// Young's modulus of the grains, Pa (see the class comment).
    float youngsModulus = 0.0f;
    /// Coefficient of restitution of every impact; in (0, 1].
    float restitution = 0.5f;
    /// Earliest simulated time at which the gate opens, s; it opens at the first frame after it
    /// in which the reservoir has settled (or maxSettleSeconds later).
    float releaseTime = 0.5f;
    /// The sand has settled when the kinetic energy per granule is below ½ m v² for this v, m/s.
    float settleSpeed = 0.02f;
    /// Longest wait for the reservoir to settle past releaseTime, s.
    float maxSettleSeconds = 2.0f;
    /// The run ends when the sand is calm at least this long after the release, s (the flow
    /// starts before it) ...
    float minDrainSeconds = 0.5f;
    /// ... or this long after the release, calm or not, s.
    float maxDrainSeconds = 8.0f;
    /// Substeps per Hertz contact time at the speed guard (WorldSettings::stepsPerContact).
    float stepsPerContact = 10.0f;
    /// Seed of the lattice's jitter and orientations: same seed, same run.
    std::uint64_t seed = 1;
  };

  ReposeScupper() = default;
  explicit ReposeScupper(const Config& config) : m_config(config) {}

  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "repose-scupper".
  std::string_view name() const override { return "repose-scupper"; }
  /// Capacity for the fill and the sump's floor; stats each frame (the settle test reads them).
  /// Throws InvalidArgument naming the field when the parameters contradict each other.
  WorldSettings worldSettings() const override;
  /// The ledge, the walls, the closed gate, the sump's floor, the sink and the fill.
  void build(World& world) override;
  /// Opens the gate once the release time has come and the fill has settled; then waits for the
  /// sand to come to rest.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_finished; }
  /// "settling", "draining", "settled", "stopped".
  std::string status() const override;
  /// In the reservoir or over the sump's floor.
  bool contains(const Vec3& centre) const override;
  /// The angle of repose and its fit (angle_of_repose_deg, flank points, R²), the pile's
  /// height, the granules in the reservoir, in the sump and lost off its end, the release time.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  SceneBounds bounds() const override;

  /// The sump's pile and its angle from the granules in `bodies` (e.g. World::readBodies at the
  /// end); throws InvalidArgument when the pile is too small to have a flank.
  analysis::HeapAngle heapAngle(std::span<const BodyState> bodies) const;
  /// Whether a granule centre (m) is over the sump's floor, away from the ledge.
  bool inSump(const Vec3& centre) const;
  /// Whether a granule centre (m) is inside the reservoir.
  bool inReservoir(const Vec3& centre) const;
  /// Simulated time at which the gate opened, s (negative before).
  double releasedAt() const { return m_releasedAt; }
  /// The fill's lattice, bottom layer first, exactly `granules` in all: every granule, at any
  /// orientation and jitter, clear of the reservoir's walls, the gate and the ledge.
  std::vector<GranuleBlock> fillBlocks() const;

 private:
  float d() const { return m_config.particleDiameter; }
  /// Granules per row (x) and rows (z) of a lattice layer in the reservoir.
  std::uint32_t rowLength() const;
  std::uint32_t rowsPerLayer() const;
  /// Height of the walls' top above the sump's floor, m.
  float wallTop() const;
  /// The gate's slab; `open` lifts it by the outlet.
  Box gate(bool open) const;
  SurfaceMaterial wallMaterial() const;
  /// The sump's rough floor.
  RoughFloor sumpFloor() const;

  Config m_config;
  ColliderId m_gate;
  float m_granuleMass = 0.0f;
  double m_releasedAt = -1.0;
  double m_finishedAt = -1.0;
  bool m_released = false;
  bool m_finished = false;
  bool m_calm = false;
};

}  // namespace sandphys::scenes
