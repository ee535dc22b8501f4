#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

struct BulldozerConfig {
  float particleDiameter = 0.02f;
  Count3 berm{6, 6, 12};
  float bladeSpeed = 0.5f;  // m/s
  float pushDistance = 24.0f;
  float pushStart = 0.8f;  // s
  float gap = 2.0f;
  float bladeHeight = 10.0f;
  float bladeOverhang = 3.0f;
  float floorFriction = 0.5f;
  float settleSpeed = 0.05f;      // m/s
  float maxSettleSeconds = 2.0f;  // s
  std::uint64_t seed = 1;
};

/// A kinematic blade pushes a berm of sand along a flat floor.
///
/// Geometry (x is the push direction, y up, z across): the floor is the plane y = 0; the berm is
/// a block of granules on it centred on x = z = 0. The blade is an upright box two diameters
/// thick, sampled into a particle shell, wider than the berm, `gap` behind it and a quarter d
/// above the floor so that it touches only the sand. At pushStart it moves `pushDistance` along
/// +x (World::moveKinematic: whole substeps, so its path does not depend on the frame lengths).
/// Scene::step stops the World where the push starts and ends, so that each reading of the
/// sand's force on the blade belongs to one phase.
class Bulldozer final : public kit::SceneWith<BulldozerConfig> {
 public:
  using SceneWith::SceneWith;

  enum class Phase { Waiting = 0, Pushing = 1, Stopped = 2 };

  /// The sand's force on the blade summed over the substeps of one phase.
  struct BladeLoad {
    double impulse[2] = {0.0, 0.0};  // Σ force · dt along x and y, N s
    std::uint64_t substeps = 0;
  };

  /// The sand's mean force on the blade over the substeps since the previous reading.
  struct DragSample {
    double time = 0.0;  // s, at the end of the substeps read
    float drag = 0.0f;  // N against the push (-x): positive when the sand resists
    Phase phase = Phase::Waiting;
  };

  std::string_view name() const override { return "bulldozer"; }
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  StepReport step(World& world, float frameDt) override;
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_course.done(); }
  std::string status() const override;
  bool contains(const Vec3& centre) const override;
  /// Blade travel and drag; the sand's shift along x and the fraction beyond the berm's front,
  /// since the push started (since build before it).
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  std::vector<SceneBody> bodies(const World& world) const override;
  SceneBounds bounds() const override;

  /// The blade in its own frame: its box's faces in square cells of 0.8 d, a particle at every
  /// corner.
  SampledMesh bladeShape() const;
  /// Where the blade's centre of mass starts, m.
  Vec3 bladeStart() const;
  /// x of the front of the blade's particles at the start, m.
  float bladeFaceStart() const;
  /// m: pushDistance, or 0 when bladeSpeed is 0.
  float bladeTravel() const;

  /// The phase the next substep belongs to.
  Phase phase() const { return m_phase; }
  const BladeLoad& load(Phase phase) const { return m_loads[static_cast<int>(phase)]; }
  const std::vector<DragSample>& dragSeries() const { return m_drag; }
  /// Substep at which the push starts and how many it lasts (0 when the blade does not move).
  std::uint64_t pushStartStep() const { return m_pushStartStep; }
  std::uint64_t pushSteps() const { return m_pushSteps; }
  /// The bodies read back when the push started and ended (empty before).
  const std::vector<BodyState>& atPushStart() const { return m_atPushStart; }
  const std::vector<BodyState>& atPushEnd() const { return m_atPushEnd; }

 private:
  std::span<const kit::Param<Config>> table() const override;
  /// The blade's box about its centre; its particle centres lie on it, m.
  TriangleMesh bladeMesh() const;
  Vec3 bladeHalfExtents() const;
  float spacing() const { return kDefaultGranuleSpacing * d(); }
  /// Height of the berm's lowest lattice centres above the floor, m.
  float bermLift() const;
  /// The World::stepCount at which the current phase ends.
  std::uint64_t phaseEnd() const;
  /// Ends the phases whose end the World has reached: their force and bodies are read.
  void endPhases(World& world);
  void readLoad(World& world);

  BodyId m_blade;
  Phase m_phase = Phase::Waiting;
  kit::Course m_course;  // acting from the start; the rest after the push
  BladeLoad m_loads[3];
  std::vector<DragSample> m_drag;
  kit::Reference m_reference;  // the berm before the push (since build before it)
  std::vector<BodyState> m_atPushStart;
  std::vector<BodyState> m_atPushEnd;
  std::uint64_t m_pushStartStep = 0;
  std::uint64_t m_pushSteps = 0;
  std::uint64_t m_stepsRun = 0;  // World::stepCount after the last frame
  double m_timeStep = 0.0;
};

}  // namespace sandphys::scenes
