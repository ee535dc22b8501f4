#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// A rock dropped into a bed of sand: a mesh file (assets/rock.obj by default, or any file assimp
/// reads) is loaded, scaled, sampled into particles (its surface, and its inside when the mesh is
/// closed) and becomes one sandphys Dynamic body. The bed, a block of granules in a smooth box,
/// settles first; then the rock appears above the middle of the bed, tilted so that it does not
/// land on a symmetric face, falls, digs into the sand and comes to rest.
///
/// Geometry: y up, the box floor at y = 0, the box centred on the y axis and sized to the bed.
/// The rock's centre of mass starts on the y axis.
class RockDrop final : public Scene {
 public:
  /// Parameters; lengths in particle diameters d unless stated.
  struct Config {
    /// Particle diameter d, m.
    float particleDiameter = 0.02f;
    /// The mesh file of the rock (OBJ, STL, PLY, glTF/GLB, ...); its coordinates times `scale`
    /// are metres. The default is assets/rock.obj of the source tree.
    std::string mesh;
    /// Factor applied to the mesh's coordinates, m per mesh unit; > 0. The default turns the
    /// 1-unit assets/rock.obj into a rock 0.14 m (7 d) long.
    float scale = 0.14f;
    /// Largest extent of the rock along x, y or z, m; > 0 scales the mesh to it (in place of
    /// `scale`), so that a mesh in any unit makes a rock of this size. 0: `scale` applies.
    float fit = 0.0f;
    /// Density of the rock, kg/m³. The default is a light stone (pumice is 400 to 1200), about
    /// the settled bed's bulk density (1100 kg/m³: granules of 0.044 kg, 4 particles of 2600
    /// kg/m³, loosely packed). The contact model's friction has no static part: below the
    /// Coulomb cap the tangential force is viscous (eq. 10), so sand under a steady load creeps
    /// like a very viscous fluid. A rock much denser than the bed (granite, 2600) keeps sinking
    /// at about 1 cm/s until it reaches the floor; one about as dense as the bed slows to a few
    /// mm/s within a second of landing, sunk in by about 1 d.
    float density = 1000.0f;
    /// Granules of the bed along x, y (layers) and z; along x and z at least, grown so that the
    /// rock, turned as it is let go, lands on sand inside the box (bedCounts()).
    Count3 bed{12, 5, 12};
    /// Gap between the settled bed's top and the rock's lowest particle when it is let go, d.
    float dropHeight = 8.0f;
    /// Angle the rock is tilted by when it is let go, degrees; [0, 90].
    float tilt = 20.0f;
    /// Earliest time at which the rock is dropped, s; it drops at the first frame after it in
    /// which the bed has settled (or maxSettleSeconds later).
    float settleTime = 0.4f;
    /// The bed has settled when the world's kinetic energy per granule is below ½ m v² for this
    /// speed v, m/s.
    float settleSpeed = 0.05f;
    /// Longest wait for the bed to settle past settleTime, s.
    float maxSettleSeconds = 3.0f;
    /// The rock is at rest when no point of it moves faster than this (|v| + |ω| · its radius)
    /// at two checks 0.1 s apart, m/s.
    float restSpeed = 0.01f;
    /// Longest wait for the rock to come to rest after the drop, s; the scene finishes anyway.
    float maxRestSeconds = 5.0f;
    /// Seed of the bed's jitter and orientations: same seed, same bed.
    std::uint64_t seed = 1;
  };

  /// Makes the scene with default parameters (Config::mesh the default rock).
  RockDrop();
  /// Makes the scene with `config`; an empty Config::mesh means the default rock.
  explicit RockDrop(const Config& config);

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  // The Scene interface (contracts in Scene).

  /// "rock-drop".
  std::string_view name() const override { return "rock-drop"; }
  /// Capacity for exactly the bed and the rock (the mesh is loaded and sampled here, and kept
  /// until Config::mesh, scale, density or the diameter change); a speed guard and time step
  /// sized for a fall from the top of the box. Throws MeshError naming the file for a mesh that
  /// cannot make a body, InvalidArgument when the rock does not fit in the box.
  WorldSettings worldSettings() const override;
  /// The box and the bed; the rock comes later, in update().
  void build(World& world) override;
  /// Adds the rock once the bed has settled (one particle read-back then, for the bed's top);
  /// afterwards reads the rock back every 0.1 s of simulated time to see whether it has stopped.
  void update(World& world, const StepReport& report, double simTime) override;
  /// True once the rock has come to rest (or maxRestSeconds after the drop).
  bool finished() const override { return m_finished; }
  /// "bed settling", "rock moving", "rock at rest t s after the drop".
  std::string status() const override;
  /// Inside the box.
  bool contains(const Vec3& centre) const override;
  /// The bed's top, the rock's depth below it, its speed and tilt, the time it took to stop.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  /// "rock", read back from `world` once it has been dropped.
  std::vector<SceneBody> bodies(const World& world) const override;
  /// Every tunable field of Config, by kebab-case name.
  std::vector<SceneParameter> parameters() override;
  /// The box.
  SceneBounds bounds() const override;

  /// Granules in the bed.
  std::uint32_t bedGranules() const;
  /// Granules of the bed along x, y and z: Config::bed, grown along x and z where the rock would
  /// reach beyond the box's inside.
  Count3 bedCounts() const;
  /// The factor from the mesh file's units to metres (Config::fit or Config::scale).
  float meshScale() const;
  /// Particles the rock is sampled into (loads the mesh if needed).
  std::uint32_t rockParticles() const;
  /// The rock's mesh, scaled to metres, in its file's frame (loads it if needed).
  const TriangleMesh& rockMesh() const;
  /// Whether the rock has been dropped, and its id then.
  bool dropped() const { return m_rock.isValid(); }
  BodyId rock() const { return m_rock; }
  /// Simulated time of the drop, s (negative before it).
  double droppedAt() const { return m_droppedAt; }
  /// Height of the settled bed's top surface, m, measured at the drop (0 before it): the median
  /// over the bed's inside of the highest grain surface in each column 2 d wide.
  float bedTop() const { return m_bedTop; }
  /// A point of the world in the rock's mesh frame (as in rockMesh()), for the rock `state`.
  Vec3 toRockFrame(const BodyState& state, const Vec3& point) const;
  /// Height of the rock mesh's lowest vertex for the rock `state`, m.
  float lowestPoint(const BodyState& state) const;

 private:
  struct LoadedRock;
  const LoadedRock& loadedRock() const;
  float d() const { return m_config.particleDiameter; }
  float halfWidth(int axis) const;
  float boxHeight() const;
  Quat dropOrientation() const;
  // Lowest and highest corner of the box around the rock mesh's vertices, relative to its centre
  // of mass, when the rock is turned by `orientation`, m.
  struct Extent {
    Eigen::Vector3f min;
    Eigen::Vector3f max;
  };
  Extent turnedExtent(const Quat& orientation) const;
  // turnedExtent(dropOrientation()), kept with the loaded rock: the box and the bed follow it.
  const Extent& dropExtent() const;
  // Below and above the centre of mass of the tilted rock, m (both >= 0).
  float rockBelow() const;
  float rockAbove() const;

  Config m_config;
  // The mesh loaded and sampled for the current parameters; settings() is const but fills it.
  mutable std::shared_ptr<const LoadedRock> m_loaded;
  float m_granuleMass = 0.0f;
  BodyId m_rock;
  double m_droppedAt = -1.0;
  float m_bedTop = 0.0f;
  Vec3 m_startUp{0.0f, 1.0f, 0.0f};  // the rock's up axis at the drop, in its own frame
  double m_nextCheck = 0.0;
  int m_calmChecks = 0;
  double m_restedAt = -1.0;
  bool m_finished = false;
};

}  // namespace sandphys::scenes
