#include "viewer/camera_control.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace sandphys::viewer {

namespace {

constexpr float kRadiansPerPixel = 0.006f;
constexpr float kZoomPerStep = 0.88f;

struct Basis {
  Eigen::Vector3f forward, right, up;
};

Basis basisOf(const render::Camera& camera) {
  Basis basis;
  basis.forward = (camera.target - camera.eye()).normalized();
  basis.right = basis.forward.cross(Eigen::Vector3f::UnitY()).normalized();
  basis.up = basis.right.cross(basis.forward);
  return basis;
}

}  // namespace

namespace camera_control {

void orbit(render::Camera& camera, float dx, float dy) {
  camera.yaw -= dx * kRadiansPerPixel;
  camera.pitch = std::clamp(camera.pitch + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void pan(render::Camera& camera, float dx, float dy, float windowHeight) {
  if (windowHeight <= 0.0f) return;
  const Basis basis = basisOf(camera);
  const float metresPerPixel = 2.0f * camera.distance * std::tan(0.5f * camera.fovY) / windowHeight;
  camera.target += metresPerPixel * (dy * basis.up - dx * basis.right);
}

void zoom(render::Camera& camera, float steps) {
  camera.distance =
      std::clamp(camera.distance * std::pow(kZoomPerStep, steps), kMinDistance, kMaxDistance);
}

Ray rayThrough(const render::Camera& camera, float x, float y, float width, float height) {
  const Basis basis = basisOf(camera);
  const float ndcX = 2.0f * x / std::max(width, 1.0f) - 1.0f;
  const float ndcY = 1.0f - 2.0f * y / std::max(height, 1.0f);
  const float tanHalf = std::tan(0.5f * camera.fovY);
  const float aspect = width / std::max(height, 1.0f);
  const Eigen::Vector3f direction =
      basis.forward + (ndcX * tanHalf * aspect) * basis.right + (ndcY * tanHalf) * basis.up;
  return {camera.eye(), direction.normalized()};
}

}  // namespace camera_control

}  // namespace sandphys::viewer
