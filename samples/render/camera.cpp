#include "render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace sandphys::render {

Eigen::Vector3f Camera::eye() const {
  const Eigen::Vector3f offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                               std::cos(pitch) * std::cos(yaw));
  return target + distance * offset;
}

Eigen::Matrix4f Camera::view() const {
  return lookAt(eye(), target, Eigen::Vector3f::UnitY());
}

Eigen::Matrix4f Camera::projection(float aspect) const {
  return perspective(fovY, aspect, 0.01f * distance, 100.0f * distance);
}

Camera Camera::framing(const scenes::SceneBounds& bounds, float aspect) {
  const Eigen::Vector3f lo(bounds.min.x, bounds.min.y, bounds.min.z);
  const Eigen::Vector3f hi(bounds.max.x, bounds.max.y, bounds.max.z);
  Camera camera;
  camera.target = 0.5f * (lo + hi);
  // The bounding sphere must fit the narrower of the two fields of view.
  const float radius = std::max(0.5f * (hi - lo).norm(), 1e-3f);
  const float halfFov = 0.5f * std::min(camera.fovY, 2.0f * std::atan(std::tan(0.5f * camera.fovY) *
                                                                      std::max(aspect, 1e-3f)));
  camera.distance = radius / std::sin(halfFov);
  return camera;
}

Eigen::Matrix4f lookAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                       const Eigen::Vector3f& up) {
  const Eigen::Vector3f f = (target - eye).normalized();
  Eigen::Vector3f s = f.cross(up);
  // Looking straight along `up`: any perpendicular will do.
  if (s.squaredNorm() < 1e-12f) s = f.cross(Eigen::Vector3f::UnitX());
  s.normalize();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f orthographic(float left, float right, float bottom, float top, float near,
                             float far) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2.0f / (right - left);
  m(1, 1) = 2.0f / (top - bottom);
  m(2, 2) = -2.0f / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

Eigen::Matrix4f perspective(float fovY, float aspect, float near, float far) {
  const float f = 1.0f / std::tan(0.5f * fovY);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2.0f * far * near / (near - far);
  m(3, 2) = -1.0f;
  return m;
}

}  // namespace sandphys::render
