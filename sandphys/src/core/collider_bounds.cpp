#include "core/collider_bounds.h"

#include <cmath>
#include <limits>

namespace sandphys::detail {
namespace {

Bounds around(Vec3 c, Vec3 half) {
  return {{c.x - half.x, c.y - half.y, c.z - half.z}, {c.x + half.x, c.y + half.y, c.z + half.z}};
}

// A wall of revolution about the vertical through `base`: radius up to `radius`, from base.y up
// `height`.
Bounds revolution(Vec3 base, float radius, float height, float margin) {
  const float r = radius + margin;
  return {{base.x - r, base.y - margin, base.z - r},
          {base.x + r, base.y + height + margin, base.z + r}};
}

}  // namespace

Bounds colliderBounds(const ColliderShape& shape, float margin) {
  if (const auto* b = std::get_if<Box>(&shape)) {
    // Any orientation: the sphere through the corners.
    const Vec3 h = b->halfExtents;
    const float r = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z) + margin;
    return around(b->center, {r, r, r});
  }
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    return revolution(c->base, c->radius, c->height, margin);
  }
  if (const auto* f = std::get_if<Funnel>(&shape)) {
    return revolution(f->outletCenter, f->outletRadius + f->height * std::tan(f->halfAngle),
                      f->height, margin);
  }
  const float big = std::numeric_limits<float>::max();
  return {{-big, -big, -big}, {big, big, big}};
}

}  // namespace sandphys::detail
