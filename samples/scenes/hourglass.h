#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct HourglassConfig {
  float particleDiameter = 0.02f;
  std::uint32_t granules = 8192;
  float outlet = 16.0f;
  float halfAngle = 22.5f;  // degrees
  float friction = 0.5f;
  float wallFriction = 0.5f;
  float youngsModulus = 0.0f;  // Pa
  float restitution = 0.5f;
  float releaseTime = 0.5f;  // s
  float settleSpeed = 0.05f;
  float maxSettleSeconds = 2.0f;
  float steadyFrom = 0.1f;
  float steadyTo = 0.8f;
  float stallSeconds = 1.0f;
  float stepsPerContact = 10.0f;
  std::uint64_t seed = 1;
};

/// The granular flow of Longmore et al. 2013 (section 6.1.5, Figs. 16, 23, 24): a fill settles
/// in an inverted cone behind a gate, then drains through the outlet at the apex at a steady
/// rate, slower with more friction and faster through a wider outlet.
///
/// Geometry (y up): a smooth Funnel with its apex at the origin, halfAngle from the y axis, cut
/// where it is `outlet` wide (so a fill settled over one outlet fits another: startFrom). The
/// gate, a slab under the outlet, slides aside at the release; a sink below removes the granules
/// that fell through, so each step's granulesAlive is the count left. The walls keep
/// wallFriction whatever the grains' μ, as the paper's containers do.
class Hourglass final : public kit::SceneWith<HourglassConfig> {
 public:
  using SceneWith::SceneWith;

  /// The line through the steady part of the drain (all 0 without one).
  struct FlowFit {
    double rate = 0.0;        ///< granules leaving per second, 1/s
    double rSquared = 0.0;    ///< of the line
    double start = 0.0;       ///< the steady window, s since the release
    double end = 0.0;         ///< s since the release
    std::size_t samples = 0;  ///< in the window; the fit needs 3
  };

  std::string_view name() const override { return "hourglass"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  /// Opens the gate once the fill has settled; then records the granules left (from the stats)
  /// until the funnel is empty or none has left for stallSeconds.
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_course.actEnd() >= 0.0; }
  std::string status() const override;
  bool contains(const Vec3& centre) const override;
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  std::vector<SceneSeries> series() const override;
  SceneBounds bounds() const override;
  /// The funnel and the sink below its outlet.
  SceneView view(const std::optional<SceneBounds>&) const override { return {bounds()}; }

  /// Makes the next build() place these granules (packingAtRelease() of an earlier run) instead
  /// of settling a lattice of `granules`; those that would reach below this run's outlet are left
  /// out. An empty list goes back to the lattice.
  void startFrom(std::vector<BodyState> packing) { m_packing = std::move(packing); }
  /// The fill just before the gate opened (one read-back); empty before.
  const std::vector<BodyState>& packingAtRelease() const { return m_packingAtRelease; }
  /// Simulated time the gate opened, s (negative before).
  double releasedAt() const { return m_course.actStart(); }
  std::uint32_t granulesAtRelease() const { return m_granulesAtRelease; }
  /// [s since the release, granules left], one sample per frame from the release on.
  const std::vector<std::array<double, 2>>& remaining() const { return m_remaining; }
  FlowFit flowFit() const;

 private:
  std::span<const kit::Param<Config>> table() const override;
  std::vector<GranuleBlock> fillRows() const;  // the lattice, one row along x per block
  std::vector<BodyState> keptPacking() const;  // startFrom's granules above this run's gate
  float halfAngle() const { return m_config.halfAngle * std::numbers::pi_v<float> / 180.0f; }
  float tanHalfAngle() const { return std::tan(halfAngle()); }
  float outletRadius() const { return 0.5f * m_config.outlet * d(); }
  float outletY() const { return outletRadius() / tanHalfAngle(); }
  float funnelTop() const;
  Box gate(bool open) const;  // open: clear of the outlet

  kit::Course m_course;
  std::vector<BodyState> m_packing;
  ColliderId m_gate;
  float m_funnelTop = 0.0f;  // m, funnelTop() at build()
  // The drain, from the release on; guard counts are WorldStats' penetration and velocity clamps.
  std::vector<BodyState> m_packingAtRelease;
  std::vector<std::array<double, 2>> m_remaining;
  std::uint32_t m_granulesAtRelease = 0;
  double m_lastDrainTime = 0.0;  // s, when the count last fell
  std::array<std::uint64_t, 2> m_guardsAtRelease{};
  std::array<std::uint64_t, 2> m_guards{};
};

}  // namespace sandphys::scenes
