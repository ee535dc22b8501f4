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

Camera Camera::framing(const scenes::SceneView& view, float aspect, float coveredLeft) {
  const Eigen::Vector3f lo(view.focus.min.x, view.focus.min.y, view.focus.min.z);
  const Eigen::Vector3f hi(view.focus.max.x, view.focus.max.y, view.focus.max.z);
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  Camera camera;
  camera.focus = view.focus;
  camera.yaw = view.yaw;
  camera.pitch = view.pitch;
  camera.target = centre;
  // The eye's frame: right, up and back (from the target to the eye).
  const Eigen::Vector3f back = (camera.eye() - camera.target).normalized();
  const Eigen::Vector3f right = Eigen::Vector3f::UnitY().cross(back).normalized();
  const Eigen::Vector3f up = back.cross(right);
  const float covered = std::clamp(coveredLeft, 0.0f, 0.9f);
  const float tanY = std::tan(0.5f * camera.fovY);
  const float tanX = tanY * std::max(aspect, 1e-3f);
  // The part of the picture left free, in tangents of the view (across / depth), with a margin.
  constexpr float kMargin = 1.0f / 1.06f;
  const float freeMiddle = tanX * covered;
  const float freeHalfX = kMargin * tanX * (1.0f - covered);
  const float freeHalfY = kMargin * tanY;
  struct Extent {
    float minX = 1e30f, maxX = -1e30f, minY = 1e30f, maxY = -1e30f;
  };
  auto extent = [&](const Camera& c) {
    const Eigen::Vector3f eye = c.eye();
    Extent e;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f d =
          Eigen::Vector3f((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                          (corner & 4) ? hi.z() : lo.z()) -
          eye;
      const float depth = -d.dot(back);
      if (depth <= 0.0f) return Extent{-1e30f, 1e30f, -1e30f, 1e30f};  // behind the eye
      e.minX = std::min(e.minX, d.dot(right) / depth);
      e.maxX = std::max(e.maxX, d.dot(right) / depth);
      e.minY = std::min(e.minY, d.dot(up) / depth);
      e.maxY = std::max(e.maxY, d.dot(up) / depth);
    }
    return e;
  };
  // At a distance, the target that puts the corners' extent in the middle of the free part
  // (moving the target across moves every corner's tangent by nearly the same amount).
  // Moving the target across moves the near corners' tangents more than the far ones', so the
  // steps are halved whenever the offset does not shrink (or a corner would go behind the eye).
  auto offset = [&](const Extent& e) {
    return Eigen::Vector2f(0.5f * (e.minX + e.maxX) - freeMiddle, 0.5f * (e.minY + e.maxY));
  };
  auto centred = [&](float distance) {
    Camera c = camera;
    c.distance = distance;
    Extent e = extent(c);
    float step = 0.5f;
    for (int pass = 0; pass < 40 && e.minX > -1e29f; ++pass) {
      const Eigen::Vector2f off = offset(e);
      Camera moved = c;
      moved.target += step * distance * (off.x() * right + off.y() * up);
      const Extent next = extent(moved);
      if (next.minX < -1e29f || offset(next).norm() >= off.norm()) {
        step *= 0.5f;
      } else {
        c = moved;
        e = next;
      }
    }
    return c;
  };
  auto fits = [&](const Camera& c) {
    const Extent e = extent(c);
    return e.maxX - freeMiddle <= freeHalfX && freeMiddle - e.minX <= freeHalfX &&
           e.maxY <= freeHalfY && -e.minY <= freeHalfY;
  };
  // The nearest distance at which the centred corners fit: between one at which the box's
  // bounding sphere surely fits and a tiny one.
  const float radius = std::max(0.5f * (hi - lo).norm(), 1e-3f);
  float far = 4.0f * radius / std::sin(std::atan(std::min(freeHalfX, freeHalfY)));
  float near = 1e-3f * radius;
  for (int i = 0; i < 40; ++i) {
    const float middle = 0.5f * (near + far);
    (fits(centred(middle)) ? far : near) = middle;
  }
  return centred(far);
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
