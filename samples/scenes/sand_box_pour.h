#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// Sand poured from above into a smooth box: an Emitter (a square rectangle high above the box
/// floor) adds granules at a fixed rate until its budget is spent, and they heap up into a pile.
/// Optionally the pour lands on a bed of sand (a block resting on the floor); the pour then
/// starts once the bed has settled.
///
/// The emitter's speed is not a parameter: it is the slowest at which the emitter's lattice can
/// take the rate (EmitterSettings::rate <= slots / layer interval), so the grains fall as gently
/// as the rate allows.
class SandBoxPour final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Pour rate, granules per second; > 0.
    float rate = 1000.0f;
    /// Granules poured in total (the emitter's budget); >= 1.
    std::uint32_t granules = 1500;
    /// Inner width of the box along x and z, d.
    float boxWidth = 40.0f;
    /// Inner height of the box, d.
    float boxHeight = 30.0f;
    /// Height of the emitting rectangle above the box floor, d.
    float emitterHeight = 20.0f;
    /// Width of the square emitting rectangle along x and z, d.
    float emitterSize = 13.0f;
    /// Optional bed: a block of granules resting on the floor before the pour, along x, y
    /// (layers) and z; a zero count means no bed.
    Count3 block{0, 0, 0};
    /// The pile (and the bed) has settled when the world's kinetic energy per granule is below
    /// ½ m v² for this speed v, m/s.
    float settleSpeed = 0.05f;
    /// Longest wait for the pile (or the bed) to settle, s; the scene finishes anyway after it.
    float maxSettleSeconds = 3.0f;
    /// Young's modulus of the grains, Pa; 0: auto (sceneYoungsModulus).
    float youngsModulus = 0.0f;
    /// Seed of the emitter and the bed: same seed, same pile.
    std::uint64_t seed = 1;
  };

  /// Makes the scene with default parameters.
  SandBoxPour() = default;
  /// Makes the scene with `config`.
  explicit SandBoxPour(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "sand-box-pour".
  std::string_view name() const override { return "sand-box-pour"; }
  /// Capacity for the bed and the emitter's whole budget; a speed guard and time step sized for
  /// the fall from the emitter. Throws InvalidArgument when the emitter or the bed does not fit
  /// in the box or the rate needs too fast an emitter.
  WorldSettings worldSettings() const override;
  /// The box, the bed and (without a bed) the emitter.
  void build(World& world) override;
  /// Starts the pour once the bed has settled; counts poured granules; detects the settled pile.
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once every granule is poured and the pile has settled (or maxSettleSeconds passed).
  bool finished() const override { return m_finished; }
  /// "poured i/n", plus "settled" at the end.
  std::string status() const override;
  /// Inside the box.
  bool contains(const Vec3& centre) const override;
  /// Granules poured, pile height and footprint radius (m and d), the box.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The box.
  SceneBounds bounds() const override;

  /// Granules in the bed (0 without one).
  std::uint32_t bedGranules() const;
  /// Granules in one layer of the emitter's lattice: the most its count can run ahead of or
  /// behind rate × time.
  std::uint32_t layerGranules() const;
  /// Downward speed of the emitted granules, m/s.
  float emitterSpeed() const;
  /// Granules the emitter has added so far (as of the last update()).
  std::uint32_t poured() const { return m_poured; }
  /// Simulated time at which the pour started, s (negative before it).
  double pourStartTime() const { return m_pourStart; }

  /// Top of the pile above the box floor, m. The pile is the contained granules slower than
  /// 0.3 m/s (not the ones still falling from the emitter); its top is the 99th percentile of
  /// their centre heights plus the granule's outer radius, so that a few bouncing grains do not
  /// count. 0 without such granules.
  float pileHeight(std::span<const BodyState> bodies) const;
  /// Radius of the pile's footprint around the pour axis, m: the 99th percentile of the pile's
  /// (see pileHeight) horizontal distances from the axis plus the granule's outer radius. 0
  /// without such granules.
  float footprintRadius(std::span<const BodyState> bodies) const;

 private:
  float d() const { return m_config.particleDiameter; }
  float halfWidth() const { return 0.5f * m_config.boxWidth * d(); }
  float emitterHalfExtent() const { return 0.5f * m_config.emitterSize * d(); }
  void startPour(World& world, double simTime);

  Config m_config;
  std::uint32_t m_poured = 0;
  double m_pourStart = -1.0;
  double m_pourEnd = -1.0;
  double m_bedDropTime = 0.0;
  // Simulated time the bed (or the last poured granule) needs to reach the floor or the pile;
  // before it, low kinetic energy only means "still falling from rest".
  double m_minSettleTime = 0.0;
  float m_granuleMass = 0.0f;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
