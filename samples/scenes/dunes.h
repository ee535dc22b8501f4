#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/pour.h"
#include "scenes/scene.h"

namespace sandphys::scenes {

/// Dune formation (Longmore et al. 2013, Fig. 25): sand dropped in two columns onto a rough floor
/// heaps into two cones that grow into each other, leaving a two-crested dune with a saddle
/// between the crests.
///
/// Geometry (y up): a rectangular rough floor (static particles, centres at y = 0), long along x;
/// two square emitters, outlet d wide, at x = ±separation/2 and pourHeight d up, pour at the
/// same rate. Grains that roll off the floor fall into a sink below it. Once the pour is done and
/// the sand has settled, one read-back gives the profile along the x axis: the highest granule
/// centre in each strip one granule wide, from the granules within a granule of the z = 0 plane.
/// The crests are the highest points of that profile on either side of x = 0, the saddle the
/// lowest point between them.
class Dunes final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    float particleDiameter = 0.02f;
    /// Granules poured by each of the two columns; >= 1.
    std::uint32_t granules = 1000;
    /// Distance between the two columns along x, d.
    float separation = 24.0f;
    /// Width of each emitter's square, d.
    float outlet = 5.0f;
    /// Pour rate of each column, granules/s.
    float rate = 400.0f;
    /// Height of the emitters above the floor, d.
    float pourHeight = 20.0f;
    /// Half length (x) and half width (z) of the rough floor, d.
    float floorHalfLength = 45.0f;
    float floorHalfWidth = 25.0f;
    /// Coulomb friction coefficient μ of every contact.
    float friction = 0.5f;
    /// Young's modulus of the grains, Pa (the soft material of the hourglass: a pour takes s).
    float youngsModulus = 0.0f;
    /// The sand has settled when its kinetic energy per granule is below ½ m v² for this v, m/s.
    float settleSpeed = 0.02f;
    /// Longest wait for the sand to settle after the pour, s.
    float maxSettleSeconds = 3.0f;
    /// Substeps per Hertz contact time at the speed guard (WorldSettings::stepsPerContact).
    float stepsPerContact = 10.0f;
    std::uint64_t seed = 1;
  };

  /// The dune's profile along x and what it shows.
  struct Profile {
    /// [x, height above the floor's top] of each strip's highest centre, m, in x order.
    std::vector<std::array<double, 2>> points;
    /// Highest point left (x < 0) and right (x > 0) of the middle, and the lowest point between
    /// them: [x, height], m.
    std::array<double, 2> leftCrest{};
    std::array<double, 2> rightCrest{};
    std::array<double, 2> saddle{};
  };

  Dunes() = default;
  explicit Dunes(const Config& config) : m_config(config) {}

  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "dunes".
  std::string_view name() const override { return "dunes"; }
  /// Capacity for both pours and the floor; stats each frame (the settle test reads them). Throws
  /// InvalidArgument naming the field when the parameters contradict each other.
  WorldSettings worldSettings() const override;
  /// The floor, the sink under it and the two emitters.
  void build(World& world) override;
  /// Waits for the pours to end and the sand to settle, then reads the bodies once for the
  /// profile.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_course.done(); }
  /// "pouring n/N", "settling", "settled" (calm) or "stopped" (the wait ran out).
  std::string status() const override;
  /// On or above the floor.
  bool contains(const Vec3& centre) const override;
  /// The two crest heights, the saddle's height and position, how deep the saddle lies below the
  /// lower crest, the crests' separation; granules on the floor.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "dune_profile": [x, height] in d, of the settled sand (empty before it settles).
  std::vector<SceneSeries> series() const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  SceneBounds bounds() const override;

  /// The profile of the granules in `bodies` (see the class comment).
  Profile profile(std::span<const BodyState> bodies) const;

 private:
  float d() const { return m_config.particleDiameter; }
  float emitterSpeed() const;

  Config m_config;
  Profile m_profile;
  kit::Course m_course;
  std::uint32_t m_poured = 0;
};

}  // namespace sandphys::scenes
