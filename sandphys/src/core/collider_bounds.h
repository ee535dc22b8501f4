#pragma once

#include "sandphys/colliders.h"

namespace sandphys::detail {

/// An axis-aligned box, lo <= hi on every axis.
struct Bounds {
  Vec3 lo;
  Vec3 hi;
};

/// A box that holds every point within `margin` of the collider's surface; a plane's is all of
/// space (the largest floats).
Bounds colliderBounds(const ColliderShape& shape, float margin);

}  // namespace sandphys::detail
