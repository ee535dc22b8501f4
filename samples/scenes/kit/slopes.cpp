#include "scenes/kit/slopes.h"

namespace sandphys::scenes::kit {

bool inBounds(const SceneBounds& bounds, const Vec3& point) {
  return point.x >= bounds.min.x && point.x <= bounds.max.x && point.y >= bounds.min.y &&
         point.y <= bounds.max.y && point.z >= bounds.min.z && point.z <= bounds.max.z;
}

Box containerBox(const SceneBounds& bounds, const SurfaceMaterial& material) {
  return Box{.center = 0.5f * (bounds.min + bounds.max),
             .halfExtents = 0.5f * (bounds.max - bounds.min),
             .inside = true,
             .material = material};
}

double meanDisplacement(const Reference& reference, std::span<const BodyState> bodies,
                        const Vec3& direction) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : granulesIn(bodies)) {
    const BodyState* before = reference.before(body);
    if (!before) continue;
    sum += dot(body.position - before->position, direction);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace sandphys::scenes::kit
