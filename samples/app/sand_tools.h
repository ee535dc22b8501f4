#pragma once

#include <cstdint>
#include <optional>

#include <sandphys/sandphys.h>
#include <Eigen/Core>

#include "scenes/scene.h"

namespace sandphys::samples {

/// A half-line in world space, m.
struct Ray {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();
  Eigen::Vector3f direction = -Eigen::Vector3f::UnitZ();  ///< unit
};

/// Where `ray` meets the horizontal plane at height `y` (m), or nothing when it points away from
/// it or runs parallel to it.
std::optional<Eigen::Vector3f> hitHorizontalPlane(const Ray& ray, float y);

/// The viewer's hands in the sand (here, beside the replay, so that a headless replay can apply a
/// recording's tool events): pours granules from an Emitter above the point under the
/// cursor, and pushes sand with a kinematic sphere of particles that follows the cursor along the
/// floor. Both work on the horizontal plane at the bottom of the scene's bounds.
class SandTools {
 public:
  /// Granules the viewer may pour on top of what the scene asks for.
  static constexpr std::uint32_t kPourGranules = 4096;
  /// Radius of the pushing sphere, in particle diameters.
  static constexpr float kSphereRadius = 6.0f;

  /// `settings` with room for the pour budget and the sphere. World::reserve is an explicit,
  /// reallocating call, so the capacity is taken up front instead of when a tool starts.
  static WorldSettings withToolCapacity(WorldSettings settings);

  /// Prepares for `world`, freshly built from `scene`. The sphere joins the world at its first
  /// push (its particles cost time in every substep), and is parked above the sand after it.
  void attach(const World& world, const scenes::Scene& scene);

  /// Call once per frame before World::step: `pour` / `push` say whether the tools are held,
  /// `cursorRay` the ray under the cursor, `frameDt` the frame's simulated duration, s.
  void update(World& world, bool pour, bool push, const Ray& cursorRay, float frameDt);

  /// Granules poured since attach().
  std::uint32_t poured() const { return m_poured; }
  /// Counts what an emitter added this frame (from StepReport::granulesEmitted).
  void countEmitted(std::uint32_t granules) { m_poured += granules; }
  /// The pushing sphere as a metal ball, once it has joined the World; null before.
  const scenes::SceneSurface* surface() const {
    return m_sphereSurface ? &*m_sphereSurface : nullptr;
  }

 private:
  // Each tool works at the point of the floor under the cursor, and stops without one.
  void updatePour(World& world, const std::optional<Vec3>& floorPoint);
  void updatePush(World& world, const std::optional<Vec3>& floorPoint, float frameDt);
  Vec3 clampToScene(Vec3 point, float margin) const;
  void addSphere(World& world);

  scenes::SceneBounds m_bounds{};
  float m_diameter = 0.02f;
  float m_maxSpeed = 10.0f;
  EmitterId m_emitter{};
  Vec3 m_emitterCentre{};
  std::uint32_t m_poured = 0;
  BodyId m_sphere{};
  std::optional<scenes::SceneSurface> m_sphereSurface;
  Vec3 m_parkedAt{};
  Vec3 m_spherePosition{};
  bool m_pushing = false;
};

}  // namespace sandphys::samples
