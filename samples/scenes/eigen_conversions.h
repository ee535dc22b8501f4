#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <sandphys/math.h>

namespace sandphys::scenes {

// sandphys' plain vectors and quaternions to and from Eigen's, for the samples' geometry.

inline Eigen::Vector3f toEigen(const Vec3& v) {
  return {v.x, v.y, v.z};
}

inline Eigen::Quaternionf toEigen(const Quat& q) {
  return {q.w, q.x, q.y, q.z};
}

inline Vec3 toVec3(const Eigen::Vector3f& v) {
  return {v.x(), v.y(), v.z()};
}

inline Quat toQuat(const Eigen::Quaternionf& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

}  // namespace sandphys::scenes
