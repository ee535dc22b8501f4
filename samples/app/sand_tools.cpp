#include "app/sand_tools.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "scenes/eigen_conversions.h"

namespace sandphys::samples {

using scenes::toEigen;
using scenes::toVec3;

namespace {

constexpr float kPourHalfExtent = 4.0f;  // d: a 9 d square, a handful of granules per layer
constexpr float kPourHeight = 40.0f;     // d above the floor plane
constexpr float kPourSpeed = 1.0f;       // m/s downward at the emitter
// The sphere hovers this far (d) above the floor plane, so that it never touches a rough floor's
// particles (their contacts would count in the stats) but still scrapes the lowest sand.
constexpr float kSphereClearance = 2.5f;

// Particle centres on a cubic lattice of spacing d inside a ball: solid, so that fast sand meets
// particles at any depth rather than slipping between those of a shell.
std::vector<Vec3> ballCentres(float radius, float d) {
  std::vector<Vec3> centres;
  const int n = static_cast<int>(std::floor(radius / d));
  for (int i = -n; i <= n; ++i) {
    for (int j = -n; j <= n; ++j) {
      for (int k = -n; k <= n; ++k) {
        if (i * i + j * j + k * k <= (radius / d) * (radius / d)) {
          centres.push_back(d * Vec3{float(i), float(j), float(k)});
        }
      }
    }
  }
  return centres;
}

}  // namespace

std::optional<Eigen::Vector3f> hitHorizontalPlane(const Ray& ray, float y) {
  if (std::abs(ray.direction.y()) < 1e-6f) return std::nullopt;
  const float t = (y - ray.origin.y()) / ray.direction.y();
  if (!(t > 0.0f) || !std::isfinite(t)) return std::nullopt;
  return Eigen::Vector3f(ray.origin + t * ray.direction);
}

WorldSettings SandTools::withToolCapacity(WorldSettings settings) {
  const std::uint32_t particles =
      settings.maxParticles ? settings.maxParticles : 4 * settings.maxBodies;
  // The lattice scales with d, so the ball's count does not depend on it.
  const auto ball = static_cast<std::uint32_t>(ballCentres(kSphereRadius, 1.0f).size());
  settings.maxBodies += kPourGranules + 1;
  settings.maxParticles = particles + 4 * kPourGranules + ball;
  return settings;
}

void SandTools::attach(const World& world, const scenes::Scene& scene) {
  *this = {};  // nothing poured, no emitter, no sphere
  m_bounds = scene.bounds();
  m_diameter = world.settings().particleDiameter;
  m_maxSpeed = world.settings().maxSpeed;

  const float radius = kSphereRadius * m_diameter;
  const Vec3 centre = 0.5f * (m_bounds.min + m_bounds.max);
  // Parked above the scene where the scene counts the point as inside its container (a closed
  // box container pushes at anything outside it), else just under the top of the bounds.
  const Vec3 above{centre.x, m_bounds.max.y + 3.0f * radius, centre.z};
  m_parkedAt =
      scene.contains(above) ? above : Vec3{centre.x, m_bounds.max.y - 1.5f * radius, centre.z};
  m_spherePosition = m_parkedAt;
}

void SandTools::addSphere(World& world) {
  const float radius = kSphereRadius * m_diameter;
  const ParticleTemplate ball = makeParticleTemplate(ballCentres(radius, m_diameter), m_diameter,
                                                     world.settings().material.density);
  m_sphere = world.addBody(ball, BodyDesc{.position = m_parkedAt, .motion = Motion::Kinematic});
  // The lattice is symmetric about its centre, so the mesh needs no shift; the outermost
  // particles reach half a diameter beyond their centres.
  m_sphereSurface = scenes::SceneSurface{m_sphere, icosphereMesh(radius + 0.5f * m_diameter, 3),
                                         ball.principalRotation, scenes::BodyMaterial::Metal};
}

Vec3 SandTools::clampToScene(Vec3 point, float margin) const {
  const float loX = m_bounds.min.x + margin, hiX = m_bounds.max.x - margin;
  const float loZ = m_bounds.min.z + margin, hiZ = m_bounds.max.z - margin;
  point.x = loX < hiX ? std::clamp(point.x, loX, hiX) : 0.5f * (loX + hiX);
  point.z = loZ < hiZ ? std::clamp(point.z, loZ, hiZ) : 0.5f * (loZ + hiZ);
  return point;
}

void SandTools::update(World& world, bool pour, bool push, const Ray& cursorRay, float frameDt) {
  std::optional<Vec3> floorPoint;
  if (const auto hit = hitHorizontalPlane(cursorRay, m_bounds.min.y)) {
    floorPoint = toVec3(*hit);
  }
  updatePour(world, pour && m_poured < kPourGranules ? floorPoint : std::nullopt);
  updatePush(world, push ? floorPoint : std::nullopt, frameDt);
}

void SandTools::updatePour(World& world, const std::optional<Vec3>& floorPoint) {
  if (!floorPoint) {
    if (m_emitter.isValid()) world.removeEmitter(m_emitter);
    m_emitter = {};
    return;
  }
  const float halfExtent = kPourHalfExtent * m_diameter;
  Vec3 centre = clampToScene(*floorPoint, halfExtent + 2.0f * m_diameter);
  centre.y = std::min(m_bounds.min.y + kPourHeight * m_diameter, m_bounds.max.y - m_diameter);
  // An emitter cannot move, so a new one replaces it; only once the cursor has left the old
  // rectangle, or the new first layer could land inside the old one's last.
  if (m_emitter.isValid()) {
    const Vec3 moved = centre - m_emitterCentre;
    if (std::max(std::abs(moved.x), std::abs(moved.z)) < 2.0f * halfExtent + 3.0f * m_diameter) {
      return;
    }
    world.removeEmitter(m_emitter);
  }
  // The emitter refuses a rate its lattice cannot take; stay well under it.
  const float spacing = kDefaultGranuleSpacing * m_diameter;
  const float perRow = 1.0f + std::floor(2.0f * halfExtent / spacing);
  m_emitter =
      world.addEmitter(EmitterSettings{.center = centre,
                                       .halfExtentX = halfExtent,
                                       .halfExtentZ = halfExtent,
                                       .rate = 0.8f * perRow * perRow * kPourSpeed / spacing,
                                       .velocity = {0.0f, -kPourSpeed, 0.0f},
                                       .maxGranules = kPourGranules - m_poured,
                                       .seed = 1 + m_poured});
  m_emitterCentre = centre;
}

void SandTools::updatePush(World& world, const std::optional<Vec3>& floorPoint, float frameDt) {
  const float radius = kSphereRadius * m_diameter;
  if (!floorPoint) {
    if (m_pushing && m_sphere.isValid()) {
      // Lifted out of the sand at once: removing overlap is harmless, unlike creating it.
      world.setBodyState(m_sphere, BodyDesc{.position = m_parkedAt, .motion = Motion::Kinematic});
      m_spherePosition = m_parkedAt;
      m_pushing = false;
    }
    return;
  }
  Vec3 goal = clampToScene(*floorPoint, radius + m_diameter);
  goal.y = m_bounds.min.y + radius + kSphereClearance * m_diameter;
  if (!m_sphere.isValid()) addSphere(world);
  if (!m_pushing) {
    // Enter above the goal and sink into place at the speed limit below, so that the sand is
    // pushed aside instead of finding a sphere inside it.
    m_spherePosition = {goal.x, std::max(m_parkedAt.y, goal.y), goal.z};
    m_pushing = true;
  }
  // A kinematic body moves with its velocity through the substeps of the frame, so the velocity
  // that reaches the goal by the end of the frame gives smooth contacts; capped well under the
  // speed guard.
  const float maxSpeed = 0.3f * m_maxSpeed;
  Vec3 velocity = (goal - m_spherePosition) / std::max(frameDt, 1e-4f);
  // Eigen's norm, whose sum is ordered x² + (y² + z²): the speed the sphere got before.
  const float speed = toEigen(velocity).norm();
  if (speed > maxSpeed) velocity = velocity * (maxSpeed / speed);
  world.setBodyState(
      m_sphere,
      BodyDesc{.position = m_spherePosition, .velocity = velocity, .motion = Motion::Kinematic});
  m_spherePosition += velocity * frameDt;
}

}  // namespace sandphys::samples
