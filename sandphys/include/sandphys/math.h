#pragma once

#include <cmath>

namespace sandphys {

/// A 3-vector in world or body space. Units are stated where it is used (SI, y is up).
struct Vec3 {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
};

/// A unit quaternion (w, x, y, z) describing an orientation; identity by default.
struct Quat {
  float w = 1.0f;
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
};

// The few operations every user of Vec3 and Quat needs, in float like the types; an engine with
// its own math library converts at its boundary (the Bullet bridge's conversions.h).

inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator-(Vec3 a) {
  return {-a.x, -a.y, -a.z};
}
inline Vec3 operator*(float s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline Vec3 operator*(Vec3 a, float s) {
  return s * a;
}
inline Vec3 operator/(Vec3 a, float s) {
  return {a.x / s, a.y / s, a.z / s};
}
inline Vec3& operator+=(Vec3& a, Vec3 b) {
  return a = a + b;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
  return a = a - b;
}
inline bool operator==(Vec3 a, Vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline float dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) {
  return std::sqrt(dot(a, a));
}
/// `a` scaled to unit length; the zero vector stays zero.
inline Vec3 normalized(Vec3 a) {
  const float l = length(a);
  return l > 0.0f ? a / l : Vec3{};
}

/// Quaternion product a · b: the rotation b, then a.
inline Quat operator*(Quat a, Quat b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
/// The inverse rotation of a unit quaternion.
inline Quat conjugate(Quat q) {
  return {q.w, -q.x, -q.y, -q.z};
}
/// The rotation by `angle` radians about the unit vector `axis` (right-handed).
inline Quat fromAxisAngle(Vec3 axis, float angle) {
  const float s = std::sin(0.5f * angle);
  return {std::cos(0.5f * angle), axis.x * s, axis.y * s, axis.z * s};
}
/// `v` turned by the unit quaternion `q`.
inline Vec3 rotate(Quat q, Vec3 v) {
  // v + 2w (u × v) + 2 u × (u × v) with u = (x, y, z): two cross products, no matrix.
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = 2.0f * cross(u, v);
  return v + q.w * t + cross(u, t);
}

}  // namespace sandphys
