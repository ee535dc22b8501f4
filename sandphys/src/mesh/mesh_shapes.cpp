// Meshes of simple solids built in code (for bodies without a file, and for tests).
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <utility>

#include "core/validation.h"
#include "sandphys/mesh.h"

namespace sandphys {

TriangleMesh boxMesh(Vec3 lo, Vec3 hi) {
  TriangleMesh mesh;
  // Corner i has x from bit 0, y from bit 1, z from bit 2.
  for (std::uint32_t i = 0; i < 8; ++i) {
    mesh.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  for (std::uint32_t axis = 0; axis < 3; ++axis) {
    const std::uint32_t u = 1u << ((axis + 1) % 3), v = 1u << ((axis + 2) % 3);
    for (std::uint32_t side = 0; side < 2; ++side) {
      const std::uint32_t base = side ? (1u << axis) : 0u;
      // (u, v, axis) is right-handed, so this order faces +axis; reverse it for the low side.
      std::array<std::uint32_t, 4> face{base, base | u, base | u | v, base | v};
      if (!side) std::swap(face[1], face[3]);
      mesh.triangles.push_back({face[0], face[1], face[2]});
      mesh.triangles.push_back({face[0], face[2], face[3]});
    }
  }
  mesh.source = "box";
  return mesh;
}

TriangleMesh cylinderMesh(double radius, double height, int segments, Vec3 centre) {
  detail::requirePositive("cylinderMesh radius", radius, "(m)");
  detail::requirePositive("cylinderMesh height", height, "(m)");
  detail::require(segments >= 3 && segments <= 4096, "cylinderMesh segments", segments,
                  "must be in 3..4096");
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(segments);
  // Vertices: bottom ring 0..n-1, top ring n..2n-1, then the bottom and top cap centres.
  for (std::uint32_t ring = 0; ring < 2; ++ring) {
    const double y = centre.y + (ring ? 0.5 : -0.5) * height;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / n;
      mesh.vertices.push_back({float(centre.x + radius * std::cos(angle)), float(y),
                               float(centre.z + radius * std::sin(angle))});
    }
  }
  const std::uint32_t bottom = 2 * n, top = 2 * n + 1;
  mesh.vertices.push_back({centre.x, float(centre.y - 0.5 * height), centre.z});
  mesh.vertices.push_back({centre.x, float(centre.y + 0.5 * height), centre.z});
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t next = (i + 1) % n;
    // With the angle running from +x towards +z, (b_i, t_i, b_next) faces outward.
    mesh.triangles.push_back({i, n + i, next});
    mesh.triangles.push_back({next, n + i, n + next});
    mesh.triangles.push_back({bottom, i, next});
    mesh.triangles.push_back({top, n + next, n + i});
  }
  mesh.source = "cylinder";
  return mesh;
}

TriangleMesh icosphereMesh(double radius, int subdivisions, Vec3 centre) {
  detail::requirePositive("icosphereMesh radius", radius, "(m)");
  detail::require(subdivisions >= 0 && subdivisions <= 8, "icosphereMesh subdivisions",
                  subdivisions, "must be in 0..8");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                         {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                         {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : points) p.normalize();
  std::vector<std::array<std::uint32_t, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0u);
      if (inserted) {
        it->second = std::uint32_t(points.size());
        points.push_back((points[a] + points[b]).normalized());
      }
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& f : faces) {
      const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                          ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  TriangleMesh mesh;
  mesh.source = "icosphere";
  for (const auto& p : points) {
    mesh.vertices.push_back({float(centre.x + radius * p.x()), float(centre.y + radius * p.y()),
                             float(centre.z + radius * p.z())});
  }
  for (auto f : faces) {
    // Wind every triangle outward, whatever the table above does.
    const Eigen::Vector3d a = points[f[0]], b = points[f[1]], c = points[f[2]];
    if ((b - a).cross(c - a).dot(a + b + c) < 0.0) std::swap(f[1], f[2]);
    mesh.triangles.push_back(f);
  }
  return mesh;
}

}  // namespace sandphys
