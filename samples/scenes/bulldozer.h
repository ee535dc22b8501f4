#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// A kinematic blade pushes a berm of sand along a flat floor.
///
/// Geometry (x is the push direction, y up, z across): the floor is a Plane at y = 0 with the
/// friction `floorFriction`. The berm is a block of granules resting on it, centred on x = z = 0,
/// by default narrow along x, tall and wide across, that slumps into a ridge while the blade
/// waits. The blade is an upright flat box, two diameters thick, whose surface is sampled into a
/// particle shell (sampleMesh; see bladeShape), wider than the berm, facing it across a small gap
/// and hovering a quarter of a particle diameter above the floor, so that it touches only the
/// sand. It is a sandphys body with Motion::Kinematic: at pushStart it starts moving along +x at
/// bladeSpeed, covers pushDistance and stops there. No side walls: sand that the blade does not
/// catch spills round its ends.
///
/// The push is a World::moveKinematic, so the blade's path is a function of the substep count
/// whatever frame lengths drive the scene: it starts at the first substep at or after pushStart
/// and lasts a whole number of substeps, at a speed within a hair of bladeSpeed that makes it end
/// exactly pushDistance on.
///
/// The sand's force on the blade is read once per frame and at the start and end of the push
/// (World::takeBodyForces; Scene::step stops the World's step there, World::step(frameDt,
/// stopAt)), so each reading belongs to one phase: waiting, pushing, stopped.
class Bulldozer final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// Granules of the berm along x (the push direction), y (layers) and z (across).
    Count3 berm{6, 6, 12};
    /// Speed of the blade during the push, m/s; [0, 5]. 0 keeps the blade where it starts.
    float bladeSpeed = 0.5f;
    /// Distance the blade travels, d; >= 0. The default takes it through the whole berm.
    float pushDistance = 24.0f;
    /// Simulated time at which the push starts, s: the berm settles until then. The default
    /// berm's kinetic energy peaks at 5 J as it slumps (0.1 s) and is below 0.01 J by 0.8 s.
    float pushStart = 0.8f;
    /// Gap between the blade's face and the nearest lattice granule's farthest reach, d.
    float gap = 2.0f;
    /// Height of the blade, d (from its bottom edge, a quarter d above the floor).
    float bladeHeight = 10.0f;
    /// How far the blade reaches beyond the berm's lattice on each side, d.
    float bladeOverhang = 3.0f;
    /// Coulomb friction coefficient of the floor against grains.
    float floorFriction = 0.5f;
    /// The sand has come to rest after the push when the world's kinetic energy per granule is
    /// below ½ m v² for this speed v, m/s.
    float settleSpeed = 0.05f;
    /// Longest wait for the sand to come to rest after the push, s.
    float maxSettleSeconds = 2.0f;
    /// Seed of the berm's jitter and orientations: same seed, same berm.
    std::uint64_t seed = 1;
  };

  /// The parts of the run, in order.
  enum class Phase { Waiting = 0, Pushing = 1, Stopped = 2 };

  /// The sand's force on the blade summed over every substep of one phase.
  struct BladeLoad {
    /// Sum over the substeps of force × time step, N s (x, y, z in the world frame).
    double impulse[3] = {0.0, 0.0, 0.0};
    /// Substeps summed.
    std::uint64_t substeps = 0;
  };

  /// One reading of the sand's force on the blade: its mean over the substeps since the previous
  /// reading (a frame, or the part of a frame before or after the push starts or ends).
  struct DragSample {
    /// Simulated time at the end of the substeps read, s.
    double time = 0.0;
    /// Mean force of the sand against the push direction (-x), N: positive when the sand
    /// resists the blade.
    float drag = 0.0f;
    /// Mean upward force of the sand on the blade, N.
    float lift = 0.0f;
    /// The phase the substeps belong to.
    Phase phase = Phase::Waiting;
  };

  /// Makes the scene with default parameters.
  Bulldozer() = default;
  /// Makes the scene with `config`.
  explicit Bulldozer(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "bulldozer".
  std::string_view name() const override { return "bulldozer"; }
  /// Capacity for exactly the berm and the blade; a speed guard well above the blade's speed.
  /// Throws InvalidArgument naming the field, value and limit for a negative length, time or
  /// friction, a blade lower than 2 d, a blade speed outside [0, 5] m/s, a berm count of 0 or a
  /// berm too large for a World.
  WorldSettings worldSettings() const override;
  /// The floor, the berm and the blade (the sampling is repeated, as settings() did it).
  void build(World& world) override;
  /// Runs the frame's substeps (stopping where the push starts or ends, to read the sand's force
  /// on the blade there) and reads the sand's force on the blade.
  StepReport step(World& world, float frameDt) override;
  /// Detects when the sand has come to rest after the push.
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once the push is over and the sand has come to rest (or maxSettleSeconds later).
  bool finished() const override { return m_finished; }
  /// "settling", "pushing 12.0/24 d, drag 95.20 N", "stopped", "stopped, sand at rest".
  std::string status() const override;
  /// Above the floor, below the bounds' top and within 20 d of their sides.
  bool contains(const Vec3& centre) const override;
  /// Blade travel; drag during the push (mean, peak) and now; since the start of the push (since
  /// build before it): the sand's centre-of-mass shift along x and the fraction of granules
  /// beyond the berm's front at that time.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "blade", read back from the World (a sync point).
  std::vector<SceneBody> bodies(const World& world) const override;
  /// Every field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The floor from behind the blade to beyond where the push leaves the sand.
  SceneBounds bounds() const override;

  /// Granules in the berm.
  std::uint32_t bermGranules() const;
  /// The blade as a particle shell, in the blade's own frame (centred on its centre of mass): its
  /// box's faces divided into square cells of 0.8 d, a particle at every corner.
  SampledMesh bladeShape() const;
  /// Where the blade's centre of mass starts, m.
  Vec3 bladeStart() const;
  /// x of the blade's face (the front of its particles) at the start, m.
  float bladeFaceStart() const;
  /// Distance the blade travels, m: pushDistance, or 0 when bladeSpeed is 0.
  float bladeTravel() const;

  /// The phase the next substep belongs to.
  Phase phase() const { return m_phase; }
  /// The blade's body (valid after build()).
  BodyId blade() const { return m_blade; }
  /// The sand's force on the blade summed over `phase` so far.
  const BladeLoad& load(Phase phase) const { return m_loads[static_cast<int>(phase)]; }
  /// Every reading of the sand's force on the blade since build().
  const std::vector<DragSample>& dragSeries() const { return m_drag; }
  /// Substep at which the push starts and substeps it lasts (0 when the blade does not move);
  /// valid after build().
  std::uint64_t pushStartStep() const { return m_pushStartStep; }
  std::uint64_t pushSteps() const { return m_pushSteps; }
  /// The bodies read back when the push started and when it ended (empty before then).
  const std::vector<BodyState>& atPushStart() const { return m_atPushStart; }
  const std::vector<BodyState>& atPushEnd() const { return m_atPushEnd; }
  /// Mass of one granule, kg (valid after build()).
  float granuleMass() const { return m_granuleMass; }

 private:
  float d() const { return m_config.particleDiameter; }
  /// The blade's half extents as a box mesh of particle centres, m.
  Vec3 bladeHalfExtents() const;
  /// Lattice spacing of the berm, m.
  float spacing() const;
  /// Height of the berm's lowest lattice centres above the floor, m.
  float bermLift() const;
  /// The World::stepCount at which the current phase ends (none for Stopped).
  std::uint64_t phaseEnd() const;
  /// Ends the phases whose end the World has reached: their force and bodies are read.
  void endPhases(World& world);
  /// Reads the sand's force on the blade into the current phase.
  void readLoad(World& world);

  Config m_config;
  BodyId m_blade;
  Phase m_phase = Phase::Waiting;
  BladeLoad m_loads[3];
  std::vector<DragSample> m_drag;
  std::vector<BodyState> m_reference;
  std::vector<BodyState> m_atPushStart;
  std::vector<BodyState> m_atPushEnd;
  std::uint64_t m_pushStartStep = 0;
  std::uint64_t m_pushSteps = 0;
  // World::stepCount after the last frame.
  std::uint64_t m_stepsRun = 0;
  double m_timeStep = 0.0;
  double m_stoppedAt = -1.0;
  float m_bermFront = 0.0f;
  float m_granuleMass = 0.0f;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
