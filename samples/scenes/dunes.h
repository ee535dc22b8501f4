#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/pour.h"

namespace sandphys::scenes {

struct DunesConfig {
  float particleDiameter = 0.02f;
  std::uint32_t granules = 1000;  // per column
  float separation = 24.0f;
  float outlet = 5.0f;
  float rate = 400.0f;  // granules/s per column
  float pourHeight = 20.0f;
  float floorHalfLength = 45.0f;
  float floorHalfWidth = 25.0f;
  float friction = 0.5f;
  float youngsModulus = 0.0f;  // Pa
  float settleSpeed = 0.02f;
  float maxSettleSeconds = 3.0f;
  float stepsPerContact = 10.0f;
  std::uint64_t seed = 1;
};

/// Dune formation (Longmore et al. 2013, Fig. 25): two square emitters at x = ±separation/2 pour
/// onto a rough floor (static particles, centres at y = 0, long along x) at the same rate; the two
/// cones grow into a dune with two crests and a saddle between them. Grains that roll off the
/// floor fall into a sink. Once the sand has settled, one read-back gives the profile.
class Dunes final : public kit::PourScene<DunesConfig> {
 public:
  using PourScene::PourScene;

  /// The dune along the x axis: the highest granule centre of each strip one granule wide, from
  /// the granules within a granule of z = 0; [x, height above the floor's top], m.
  struct Profile {
    std::vector<std::array<double, 2>> points;  // in x order
    /// The highest point on either side of x = 0, and the lowest point between them.
    std::array<double, 2> leftCrest{}, rightCrest{}, saddle{};
  };

  std::string_view name() const override { return "dunes"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  void update(World& world, const StepReport& report, double simTime) override;
  bool contains(const Vec3& centre) const override;  // on or above the floor
  /// The crests, the saddle and its depth below the lower crest, the granules on the floor.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "dune_profile": [x, height] in d, of the settled sand (empty before it settles).
  std::vector<SceneSeries> series() const override;
  SceneBounds bounds() const override;

  Profile profile(std::span<const BodyState> bodies) const;

 private:
  std::span<const kit::Param<Config>> table() const override;
  RoughFloor roughFloor() const;  // long along x

  Profile m_profile;
};

}  // namespace sandphys::scenes
