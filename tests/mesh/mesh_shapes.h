#pragma once

#include <sandphys/sandphys.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sandphys::mesh_testing {

/// Corners and faces of an axis-aligned box; each face lists its four corners counter-clockwise
/// seen from outside.
struct BoxQuads {
  std::vector<Vec3> corners;
  std::vector<std::array<std::uint32_t, 4>> faces;
};
BoxQuads boxQuads(Vec3 lo, Vec3 hi);

/// sandphys::boxMesh with `name` as its source (error messages quote it).
TriangleMesh namedBox(Vec3 lo, Vec3 hi, const std::string& name);

/// sandphys::icosphereMesh with `name` as its source.
TriangleMesh namedIcosphere(double radius, int subdivisions, Vec3 centre, const std::string& name);

/// Every vertex mapped to rotation · v + translation.
TriangleMesh transformed(TriangleMesh mesh, const Eigen::Matrix3d& rotation,
                         const Eigen::Vector3d& translation);

/// Points spread uniformly over the area of the mesh (fixed seed: the same points every run).
std::vector<Eigen::Vector3d> randomSurfacePoints(const TriangleMesh& mesh, std::size_t count,
                                                 std::uint32_t seed);

/// Distance from `p` to the nearest of `points` (brute force: the meshes here are small).
double nearestDistance(const std::vector<Vec3>& points, const Eigen::Vector3d& p);

/// For each point, the distance to its nearest other point.
std::vector<double> nearestNeighbourDistances(const std::vector<Vec3>& points);

inline Eigen::Vector3d toEigen(const Vec3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace sandphys::mesh_testing
