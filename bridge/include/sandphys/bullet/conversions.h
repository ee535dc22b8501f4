#pragma once

// Conversions between sandphys and Bullet vectors and quaternions (both single precision here).

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

#include <sandphys/math.h>

namespace sandphys::bullet {

inline Vec3 toSand(const btVector3& v) {
  return {float(v.x()), float(v.y()), float(v.z())};
}

inline btVector3 toBullet(const Vec3& v) {
  return {btScalar(v.x), btScalar(v.y), btScalar(v.z)};
}

inline Quat toSand(const btQuaternion& q) {
  return {float(q.w()), float(q.x()), float(q.y()), float(q.z())};
}

}  // namespace sandphys::bullet
