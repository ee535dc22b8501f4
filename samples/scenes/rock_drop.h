#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"

namespace sandphys::scenes {

/// assets/rock.obj of the source tree, the default rock.
std::string defaultRockMesh();

struct RockDropConfig {
  float particleDiameter = 0.02f;
  std::string mesh = defaultRockMesh();
  float scale = 0.14f;      // m per mesh unit
  float fit = 0.0f;         // m
  float density = 1000.0f;  // kg/m³
  Count3 bed{12, 5, 12};
  float dropHeight = 8.0f;
  float tilt = 20.0f;       // degrees
  float settleTime = 0.4f;  // s
  float settleSpeed = 0.05f;
  float maxSettleSeconds = 3.0f;
  float restSpeed = 0.01f;  // m/s
  float maxRestSeconds = 5.0f;
  std::uint64_t seed = 1;
};

/// A rock dropped into a bed of sand: a mesh (any file assimp reads), scaled and sampled into one
/// Dynamic body (filled when the mesh is closed). The bed, a block of granules in a smooth box
/// (floor at y = 0, centred on the y axis), settles first; then its top is read back once and the
/// rock appears above its middle, turned so that it lands on an edge, falls, digs in and comes to
/// rest (read back every 0.1 s of simulated time to see whether it has stopped).
class RockDrop final : public kit::SceneWith<RockDropConfig> {
 public:
  using SceneWith::SceneWith;

  std::string_view name() const override { return "rock-drop"; }
  /// Loads and samples the mesh (kept while mesh, scale, fit, density, tilt and d stay); throws
  /// MeshError naming the file for a mesh that cannot make a body.
  WorldSettings worldSettings() const override;
  void build(World& world) override;
  void update(World& world, const StepReport& report, double simTime) override;
  bool finished() const override { return m_run.finished; }
  std::string status() const override;
  /// The bed's top, the rock's lowest point and depth below it, its speed and tilt, the time it
  /// took to stop.
  std::vector<SceneMetric> metrics(std::span<const BodyState> bodies) const override;
  std::vector<SceneBody> bodies(const World& world) const override;
  SceneBounds bounds() const override;

  /// Config::bed, grown along x and z until the box holds the rock as it is let go.
  Count3 bedCounts() const;
  /// The rock's mesh, scaled to metres, in its file's frame.
  const TriangleMesh& rockMesh() const;
  bool dropped() const { return m_run.rock.isValid(); }
  BodyId rock() const { return m_run.rock; }
  double droppedAt() const { return m_course.actStart(); }  // s, negative before the drop

 private:
  struct LoadedRock;
  std::span<const kit::Param<Config>> table() const override;
  const LoadedRock& loadedRock() const;
  float halfWidth(int axis) const;
  float boxHeight() const;
  float bedTopOf(std::span<const ParticleState> particles) const;
  void drop(World& world, double simTime);
  bool atRest() const;

  // The mesh loaded and sampled for the current parameters; settings() is const but fills it.
  mutable std::shared_ptr<const LoadedRock> m_loaded;
  kit::Course m_course;  // the bed's settle and the drop
  struct Run {
    BodyId rock;
    // The settled bed's top at the drop, m: the median, over the bed's inside, of the highest
    // grain surface in each column kTopColumn d wide.
    float bedTop = 0.0f;
    Vec3 startUp{0.0f, 1.0f, 0.0f};  // the rock's up axis at the drop, in its own frame
    double nextCheck = 0.0;          // of the rock's speed, s
    int calmChecks = 0;              // in a row
    double restedAt = -1.0;          // s, the first of those
    bool finished = false;
  } m_run;
};

}  // namespace sandphys::scenes
