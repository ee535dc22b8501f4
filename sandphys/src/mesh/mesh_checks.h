#pragma once

#include <Eigen/Core>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sandphys/error.h"
#include "sandphys/math.h"
#include "sandphys/mesh.h"

namespace sandphys::mesh_detail {

/// How messages name a mesh: "mesh 'path/rock.obj'", or "mesh (built in code, no
/// TriangleMesh::source)" when its source is empty.
std::string meshName(const std::string& source);
inline std::string meshName(const TriangleMesh& mesh) {
  return meshName(mesh.source);
}

/// Throws MeshError "<mesh name>: <problem>".
[[noreturn]] void throwMeshError(const std::string& source, const std::string& problem);

/// "(x, y, z)" with the value formatting of error messages (NaN and infinities spelled out).
std::string formatPoint(double x, double y, double z);

inline Eigen::Vector3d toEigen(const Vec3& v) {
  return {v.x, v.y, v.z};
}

/// Corners of the axis-aligned box around the vertices the triangles use, m.
struct MeshBounds {
  Eigen::Vector3d lo;
  Eigen::Vector3d hi;
};
MeshBounds boundsOfTriangles(const TriangleMesh& mesh);

/// A vertex position as its bit pattern, -0 made +0: equal keys mean equal positions.
struct PositionKey {
  std::uint32_t x, y, z;
  explicit PositionKey(const Vec3& v) : x(bits(v.x)), y(bits(v.y)), z(bits(v.z)) {}
  bool operator==(const PositionKey&) const = default;

 private:
  static std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f + 0.0f); }
};

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h = (h ^ k.y) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ k.z) * 0x94D049BB133111EBull;
    return std::size_t(h ^ (h >> 31));
  }
};

/// For each vertex, the first vertex at the same position: triangles that repeat a corner per
/// face (STL, a cube with per-face normals) then share it.
std::vector<std::uint32_t> firstVertexAtPosition(const TriangleMesh& mesh);

/// False for a triangle of zero area within float rounding: twice its area at most 1e-6 of its
/// longest edge squared (collinear corners, or a repeated one).
bool hasArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace sandphys::mesh_detail
