#include "mesh/mesh_shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>

namespace sandphys::mesh_testing {

BoxQuads boxQuads(Vec3 lo, Vec3 hi) {
  // The library's box is two triangles (f0, f1, f2), (f0, f2, f3) per face, in face order.
  const TriangleMesh mesh = boxMesh(lo, hi);
  BoxQuads box;
  box.corners = mesh.vertices;
  for (std::size_t t = 0; t + 1 < mesh.triangles.size(); t += 2) {
    const auto& a = mesh.triangles[t];
    box.faces.push_back({a[0], a[1], a[2], mesh.triangles[t + 1][2]});
  }
  return box;
}

TriangleMesh namedBox(Vec3 lo, Vec3 hi, const std::string& name) {
  TriangleMesh mesh = boxMesh(lo, hi);
  mesh.source = name;
  return mesh;
}

TriangleMesh namedIcosphere(double radius, int subdivisions, Vec3 centre, const std::string& name) {
  TriangleMesh mesh = icosphereMesh(radius, subdivisions, centre);
  mesh.source = name;
  return mesh;
}

TriangleMesh transformed(TriangleMesh mesh, const Eigen::Matrix3d& rotation,
                         const Eigen::Vector3d& translation) {
  for (Vec3& v : mesh.vertices) {
    const Eigen::Vector3d p = rotation * toEigen(v) + translation;
    v = {float(p.x()), float(p.y()), float(p.z())};
  }
  return mesh;
}

std::vector<Eigen::Vector3d> randomSurfacePoints(const TriangleMesh& mesh, std::size_t count,
                                                 std::uint32_t seed) {
  std::vector<double> cumulative;
  double total = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    total +=
        0.5 * (toEigen(mesh.vertices[tri[1]]) - a).cross(toEigen(mesh.vertices[tri[2]]) - a).norm();
    cumulative.push_back(total);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double pick = uniform(rng) * total;
    const std::size_t t = std::min<std::size_t>(
        std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
        cumulative.size() - 1);
    // Uniform on a triangle: fold the unit square onto it.
    double r = uniform(rng), s = uniform(rng);
    if (r + s > 1.0) {
      r = 1.0 - r;
      s = 1.0 - s;
    }
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    out.push_back(a + r * (toEigen(mesh.vertices[tri[1]]) - a) +
                  s * (toEigen(mesh.vertices[tri[2]]) - a));
  }
  return out;
}

double nearestDistance(const std::vector<Vec3>& points, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& q : points) best = std::min(best, (toEigen(q) - p).squaredNorm());
  return std::sqrt(best);
}

std::vector<double> nearestNeighbourDistances(const std::vector<Vec3>& points) {
  std::vector<double> out(points.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      const double d = (toEigen(points[i]) - toEigen(points[j])).squaredNorm();
      out[i] = std::min(out[i], d);
      out[j] = std::min(out[j], d);
    }
  }
  for (double& d : out) d = std::sqrt(d);
  return out;
}

}  // namespace sandphys::mesh_testing
