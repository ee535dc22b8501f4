#include "scenes/kit/geometry.h"

#include <algorithm>
#include <cmath>

namespace sandphys::scenes::kit {

GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed) {
  return {.center = {0.0f, lift + 0.5f * blockSpan(counts[1], spacing), 0.0f},
          .countX = counts[0],
          .countY = counts[1],
          .countZ = counts[2],
          .spacing = spacing,
          .seed = seed};
}

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

void addCylinderContainer(World& world, float radius, float height, float d) {
  world.addCollider(Cylinder{.base = {0.0f, 0.0f, 0.0f}, .radius = radius, .height = height});
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d});
  world.addCollider(Plane{.normal = {0.0f, 1.0f, 0.0f}, .offset = -d});
}

}  // namespace sandphys::scenes::kit
