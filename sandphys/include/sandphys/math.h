#pragma once

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

}  // namespace sandphys
