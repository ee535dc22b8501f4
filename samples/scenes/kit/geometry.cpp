#include "scenes/kit/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>

namespace sandphys::scenes::kit {

float tiltDegrees(const Quat& q) {
  const float up = std::clamp(1.0f - 2.0f * (q.x * q.x + q.z * q.z), -1.0f, 1.0f);
  return std::acos(up) * 180.0f / std::numbers::pi_v<float>;
}

GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed) {
  return {.center = {0.0f, lift + 0.5f * blockSpan(counts[1], spacing), 0.0f},
          .countX = counts[0],
          .countY = counts[1],
          .countZ = counts[2],
          .spacing = spacing,
          .seed = seed};
}

std::vector<LatticeRun> discRuns(std::uint32_t columns) {
  const auto half = static_cast<std::int32_t>(std::ceil(std::sqrt(columns / 3.14159265))) + 2;
  std::vector<std::array<std::int32_t, 3>> sites;  // (x² + z², z, x)
  for (std::int32_t j = -half; j <= half; ++j) {
    for (std::int32_t i = -half; i <= half; ++i) sites.push_back({i * i + j * j, j, i});
  }
  std::sort(sites.begin(), sites.end());
  sites.resize(columns);
  std::sort(sites.begin(), sites.end(), [](const auto& a, const auto& b) {
    return std::tie(a[1], a[2]) < std::tie(b[1], b[2]);
  });
  std::vector<LatticeRun> runs;
  for (const auto& [r2, j, i] : sites) {
    if (runs.empty() || runs.back().row != j) runs.push_back({j, i, 0});
    ++runs.back().count;
  }
  return runs;
}

double discRadius(std::span<const LatticeRun> runs) {
  double farthest = 0.0;
  for (const LatticeRun& run : runs) {
    for (std::int32_t i : {run.first, run.first + std::int32_t(run.count) - 1}) {
      farthest = std::max(farthest, std::hypot(double(i), double(run.row)));
    }
  }
  return farthest;
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
