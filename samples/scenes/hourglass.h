#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// The granular-flow test of Longmore et al. 2013 (section 6.1.5, Fig. 16, results in Fig. 23
/// and 24): an inverted cone filled with granules drains through an outlet of diameter D at its
/// apex; the granules left in the cone fall linearly with time (a constant mean flow rate, which
/// is what makes an hourglass work), more slowly with more friction and faster with a larger D
/// (Beverloo's law).
///
/// Geometry (y up): a cone with its apex at the origin, opening upward around the y axis, sliced
/// across where it is D wide, which removes the apex and leaves the outlet (as the paper builds
/// its funnel). The cone does not depend on D, so a fill settled over one outlet also fits
/// another (see startFrom). The funnel is a smooth Funnel wall. The paper's "aperture of 45
/// degrees" is read as the full opening angle of the cone, so the wall stands halfAngle = 22.5°
/// from the vertical axis (67.5° from horizontal). A gate (a solid slab whose top is the outlet
/// plane) closes the outlet while the granules, laid on a lattice inside the cone, settle; at the
/// release it slides sideways, clear of the stream. A Sink whose top is kSinkDepth d below the
/// outlet removes every granule that has fallen through, so the world's own count of granules
/// alive (WorldStats::granulesAlive, read with every step's stats at no extra cost) is the count
/// remaining in the funnel, short of the few in the 2 d of free fall.
///
/// Where it differs from the paper, and why:
/// - The paper's floor 50 d below the outlet, where a pile forms, is left out: the pile does not
///   change the flow while it stays below the outlet, and its granules would cost substeps.
/// - `friction` is the μ of grain-grain contacts (eq. 10, the paper's variable in Fig. 23);
///   the funnel wall and the gate have their own, `wallFriction`, held at 0.5 as the paper holds
///   its containers' for the angle of repose against μ (Fig. 22), so that a sweep over μ changes
///   the grains alone.
/// - The paper asks for a fill at least 2.5 times as high as it is wide, W > D + 30 d (the
///   conditions for a constant mean flow, its ref. [8]) and uses 64 K granules. The defaults
///   hold 8192 granules over the paper's outlet (D = 16 d), which settle 38 d high and 48 d
///   wide (the metrics report both): lower than wide. A cone 22.5° from the axis is never 2.5
///   times higher than wide, and the flow stays steady regardless: the default run drains at a
///   constant rate (R² > 0.999) until the last few hundred granules. The steady window leaves
///   out the end, where a low fill would matter.
/// - A softer material than the library's (Young's modulus 2e6 Pa against 5e6 Pa): the time
///   step is a fraction of the Hertz contact time, which grows as E^-2/5 (1.4 times longer
///   here), and a drain takes seconds. The default run's rate over the same window is 2148
///   granules/s at 2e6 Pa and 2117 at 5e6 Pa; its penetration guard (d/10, beyond which the
///   Hertz force stops growing) fires in about 1 of 1000 contacts while draining at 2e6 Pa and
///   almost never at 5e6 Pa. Softer still fails: at 5e5 Pa the weight of a fill of a thousand
///   granules pushes a fifth of its contacts past the guard, and granules sink into each other.
/// - The lattice the fill starts on is loose (solid fraction 0.2; random orientations need
///   2.225 d between centres) and collapses to about two thirds of its height before the gate
///   opens, which fires the speed and penetration guards; the metrics count the guards while
///   draining apart.
///
/// The flow rate is the slope of a least-squares line through the (time, granules remaining)
/// samples of the steady part: from when a fraction steadyFrom of the granules has left (the
/// start-up, when the arch over the outlet breaks and the packing dilates, lies before it) until
/// a fraction steadyTo has left or the run ends, whichever comes first (the last granules drain
/// from a fill lower than the outlet is wide, where the rate may fall; in the default run it
/// hardly does).
class Hourglass final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Granules in the funnel; >= 1.
    std::uint32_t granules = 8192;
    /// Outlet diameter D, d; the paper's outlet radius is 8 d (Fig. 16) and its D ranges over
    /// 8 to 24 d (Fig. 24). 0 closes the funnel. Small outlets jam, the sooner the higher the
    /// friction: at μ = 0.8 a fill of 1500 granules jammed over 10 d.
    float outlet = 16.0f;
    /// Angle of the funnel wall from the vertical axis, degrees; in (0, 80].
    float halfAngle = 22.5f;
    /// Coulomb friction coefficient μ of grain-grain contacts.
    float friction = 0.5f;
    /// Coulomb friction coefficient of the funnel wall and the gate.
    float wallFriction = 0.5f;
    /// Young's modulus of the grains, Pa (see the class comment).
    float youngsModulus = 0.0f;
    /// Coefficient of restitution of grain-grain and grain-wall impacts; in (0, 1].
    float restitution = 0.5f;
    /// Earliest simulated time at which the gate opens, s; it opens at the first frame after it
    /// in which the fill has settled (or maxSettleSeconds later).
    float releaseTime = 0.5f;
    /// The fill has settled when the world's kinetic energy per granule is below ½ m v² for
    /// this speed v, m/s.
    float settleSpeed = 0.05f;
    /// Longest wait for the fill to settle past releaseTime, s.
    float maxSettleSeconds = 2.0f;
    /// The steady part of the drain starts once this fraction of the granules has left; [0, 1).
    float steadyFrom = 0.1f;
    /// The steady part ends once this fraction has left; (steadyFrom, 1].
    float steadyTo = 0.8f;
    /// The scene is finished when the funnel is empty, or when no granule has left for this
    /// long after the release (a jammed or closed outlet), s.
    float stallSeconds = 1.0f;
    /// Substeps per Hertz contact time at the speed guard (WorldSettings::stepsPerContact);
    /// >= kMinStepsPerContact. Contacts slower than the guard get more.
    float stepsPerContact = 10.0f;
    /// Seed of the fill's jitter and orientations: same seed, same fill.
    std::uint64_t seed = 1;
  };

  /// The straight line through the steady part of the drain (see the class comment).
  struct FlowFit {
    /// Granules leaving per second (the negated slope), 1/s; 0 without a steady part.
    double rate = 0.0;
    /// R² of the line; 0 without a steady part.
    double rSquared = 0.0;
    /// The steady window, s since the release.
    double start = 0.0;
    double end = 0.0;
    /// Samples in the window; the fit needs at least 3 (else the fields above are 0).
    std::size_t samples = 0;
  };

  /// Makes the scene with default parameters.
  Hourglass() = default;
  /// Makes the scene with `config`.
  explicit Hourglass(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "hourglass".
  std::string_view name() const override { return "hourglass"; }
  /// Capacity for exactly the fill; the soft material, stats each frame (the count of granules
  /// remaining is read from them) and a speed guard for the fall through the outlet. Throws
  /// InvalidArgument naming the field when the parameters contradict each other.
  WorldSettings worldSettings() const override;
  /// The funnel, the closed gate, the sink and the fill.
  void build(World& world) override;
  /// Opens the gate once the release time has come and the fill has settled; after that records
  /// the granules remaining (from the step's stats: no read-back) and detects the end.
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once the funnel is empty or has stopped draining (see Config::stallSeconds).
  bool finished() const override { return m_finished; }
  /// "settling", "draining: n left", "empty", "stopped: n left".
  std::string status() const override;
  /// In the funnel built last, or below the outlet above the sink.
  bool contains(const Vec3& centre) const override;
  /// Granules at release and in the funnel, the fill's height and width at release, release
  /// time, flow rate and R² of the steady part, guard counts while draining.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "remaining": [s since the release, granules] at every frame from the release on, with
  /// flow_rate (granules/s), flow_rate_r2 and the steady window (flow_steady_start_s,
  /// flow_steady_end_s, flow_steady_samples).
  std::vector<SceneSeries> series() const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The funnel and the fall to the sink.
  SceneBounds bounds() const override;

  /// Radius of the outlet, m.
  float outletRadius() const { return 0.5f * m_config.outlet * d(); }
  /// Height of the outlet plane above the cone's apex (the origin), m.
  float outletY() const;
  /// Height of the funnel's top rim above the apex, m: the fill and some headroom.
  float funnelTop() const;

  /// Makes the next build() place these granules (position and orientation; e.g.
  /// packingAtRelease() of an earlier run, which settled over any outlet) instead of laying out
  /// and settling a lattice; Config::granules is then not used. Granules that would reach below
  /// this run's outlet plane (a larger outlet slices the cone higher) are left out. An empty list
  /// goes back to the lattice.
  void startFrom(std::vector<BodyState> packing) { m_packing = std::move(packing); }
  /// The granules in the funnel just before the gate opened (one World::readBodies then, a sync
  /// point once per run); empty before the release.
  const std::vector<BodyState>& packingAtRelease() const { return m_packingAtRelease; }
  /// Whether the gate has opened.
  bool released() const { return m_released; }
  /// Simulated time at which the gate opened, s (negative before).
  double releasedAt() const { return m_releasedAt; }
  /// Granules in the funnel when the gate opened (0 before).
  std::uint32_t granulesAtRelease() const { return m_granulesAtRelease; }
  /// [s since the release, granules remaining], one sample per frame from the release on.
  const std::vector<std::array<double, 2>>& remaining() const { return m_remaining; }
  /// The line through the steady part of remaining() (sandphys::analysis::fitLine).
  FlowFit flowFit() const;

  /// Depth of the sink's top below the outlet plane, d: a granule whose centre is that deep is
  /// wholly through the outlet (its reach is 1.11 d).
  static constexpr float kSinkDepth = 2.0f;

 private:
  /// One row of the fill's lattice: `count` granules along x centred on `center`.
  struct Row {
    Vec3 center{};
    std::uint32_t count = 0;
  };
  /// The fill: lattice rows inside the cone, bottom layer first, exactly `granules` in all.
  std::vector<Row> fillRows() const;
  /// The granules of startFrom's packing that this run places (alive, clear of the gate).
  std::vector<BodyState> keptPacking() const;
  /// Highest granule centre of the fill, m.
  float fillTop() const;
  /// Adds startFrom's packing to `world`.
  void addPacking(World& world) const;
  float d() const { return m_config.particleDiameter; }
  float tanHalfAngle() const;
  /// The gate's slab; `open` slides it sideways clear of the outlet.
  Box gate(bool open) const;

  Config m_config;
  std::vector<BodyState> m_packing;
  std::vector<BodyState> m_packingAtRelease;
  ColliderId m_gate;
  float m_funnelTop = 0.0f;  ///< funnelTop() at build(), m
  std::vector<std::array<double, 2>> m_remaining;
  double m_releasedAt = -1.0;
  double m_lastDrainTime = 0.0;
  float m_granuleMass = 0.0f;
  std::uint32_t m_granulesAtRelease = 0;
  std::uint32_t m_lastRemaining = 0;
  // Penetration and velocity guard counts (WorldStats) at the release and at the latest frame.
  std::array<std::uint64_t, 2> m_guardsAtRelease{};
  std::array<std::uint64_t, 2> m_guards{};
  bool m_released = false;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
