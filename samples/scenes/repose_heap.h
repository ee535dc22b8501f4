#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/analysis/heap.h>

#include "scenes/pour.h"
#include "scenes/scene.h"

namespace sandphys::scenes {

/// The angle of repose of a poured heap (Longmore et al. 2013, section 6.1.4, Fig. 22): a narrow
/// emitter high above the middle of a rough floor pours granules at a steady rate; the heap that
/// forms under it is a cone whose flank stands at the material's angle of repose, steeper with
/// more friction. Once the pour is done and the heap has settled, the angle comes from a robust
/// (bisquare) line through the heap's surface granules (sandphys::analysis::angleOfRepose).
///
/// Geometry (y up): a rough floor (a disc of static particles, the paper's "rough floor", whose
/// centres are at y = 0) of radius floorRadius around the y axis; the emitter's square, outlet d
/// wide, at pourHeight d above it. Grains that roll off the floor's edge fall into a sink: the
/// heap keeps the floor's size at most, as a heap poured onto a table does.
///
/// Where it differs from the paper, and why:
/// - The paper measures the angle in the sump of its reservoir-and-scupper setup (Fig. 15); a
///   heap poured from above is the simpler classic and needs no reservoir to fill and drain.
/// - The floor is made of particles, so its friction is the grains' μ (the paper fixes the floor
///   and wall friction at 0.5). Its roughness (particles one diameter apart) holds the bottom
///   layer of the heap in place whatever μ is.
/// - The softer material of the hourglass scene (Young's modulus 2e6 Pa): a pour takes seconds.
class ReposeHeap final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Granules poured; >= 1.
    std::uint32_t granules = 3000;
    /// Coulomb friction coefficient μ of every contact (grains and floor particles).
    float friction = 0.5f;
    /// Width of the emitter's square, d: the "outlet" the sand pours from.
    float outlet = 5.0f;
    /// Pour rate, granules/s.
    float rate = 400.0f;
    /// Height of the emitter above the floor, d; it stays there, so it has to clear the heap.
    float pourHeight = 20.0f;
    /// Radius of the rough floor, d.
    float floorRadius = 40.0f;
    /// Young's modulus of the grains, Pa (see the class comment).
    float youngsModulus = 0.0f;
    /// Coefficient of restitution of every impact; in (0, 1].
    float restitution = 0.5f;
    /// The heap has settled when the kinetic energy per granule is below ½ m v² for this v, m/s.
    float settleSpeed = 0.02f;
    /// Longest wait for the heap to settle after the pour, s.
    float maxSettleSeconds = 3.0f;
    /// Substeps per Hertz contact time at the speed guard (WorldSettings::stepsPerContact).
    float stepsPerContact = 10.0f;
    /// Seed of the emitter's orientations: same seed, same heap.
    std::uint64_t seed = 1;
  };

  ReposeHeap() = default;
  explicit ReposeHeap(const Config& config) : m_config(config) {}

  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "repose-heap".
  std::string_view name() const override { return "repose-heap"; }
  /// Capacity for the pour and the floor; stats each frame (the settle test reads them). Throws
  /// InvalidArgument naming the field when the parameters contradict each other.
  WorldSettings worldSettings() const override;
  /// The floor, the sink under it and the emitter.
  void build(World& world) override;
  /// Waits for the pour to end and the heap to settle.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_settling.settled(); }
  /// "pouring n/N", "settling", "settled" (calm) or "stopped" (the wait ran out).
  std::string status() const override;
  /// On or above the floor, within its radius.
  bool contains(const Vec3& centre) const override;
  /// The angle of repose and its fit (angle_of_repose_deg, flank points, R²), the heap's height
  /// and the granules on the floor and lost over its edge, the pour's timing.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  SceneBounds bounds() const override;

  /// The heap's surface and angle from the granules in `bodies` (e.g. World::readBodies at the
  /// end); throws InvalidArgument when the heap is too small to have a flank.
  analysis::HeapAngle heapAngle(std::span<const BodyState> bodies) const;
  /// Speed of the emitter's granules, m/s.
  float emitterSpeed() const;
  /// Floor radius, d, on which a cone of `granules` settled granules with its flank at
  /// `angleDegrees` ends a margin short of the edge: for a floor that follows the pour's size.
  static float floorRadiusHolding(std::uint32_t granules, float angleDegrees);

 private:
  float d() const { return m_config.particleDiameter; }

  Config m_config;
  PourSettling m_settling{0.0, 0.0f, 0.0f, 0.0f};  // set by build()
  std::uint32_t m_poured = 0;
};

}  // namespace sandphys::scenes
