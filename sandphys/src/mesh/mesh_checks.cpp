#include "mesh/mesh_checks.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "core/validation.h"

namespace sandphys {
namespace mesh_detail {

std::string meshName(const std::string& source) {
  return source.empty() ? std::string("mesh (built in code, no TriangleMesh::source)")
                        : "mesh '" + source + "'";
}

void throwMeshError(const std::string& source, const std::string& problem) {
  throw MeshError(meshName(source) + ": " + problem);
}

std::string formatPoint(double x, double y, double z) {
  // Appended piece by piece: GCC 12 warns wrongly (-Wrestrict) about "(" + std::string.
  std::string text;
  text.append("(").append(detail::formatValue(x)).append(", ");
  text.append(detail::formatValue(y)).append(", ").append(detail::formatValue(z)).append(")");
  return text;
}

std::vector<std::uint32_t> firstVertexAtPosition(const TriangleMesh& mesh) {
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> first;
  first.reserve(mesh.vertices.size());
  std::vector<std::uint32_t> ids(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    ids[i] = first.try_emplace(PositionKey(mesh.vertices[i]), std::uint32_t(i)).first->second;
  }
  return ids;
}

bool hasArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() > 1e-6 * longest;
}

MeshBounds boundsOfTriangles(const TriangleMesh& mesh) {
  MeshBounds b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
               Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (const auto& tri : mesh.triangles) {
    for (std::uint32_t i : tri) {
      b.lo = b.lo.cwiseMin(toEigen(mesh.vertices[i]));
      b.hi = b.hi.cwiseMax(toEigen(mesh.vertices[i]));
    }
  }
  return b;
}

}  // namespace mesh_detail

void validateMesh(const TriangleMesh& mesh) {
  using mesh_detail::throwMeshError;
  if (mesh.triangles.empty()) {
    throwMeshError(mesh.source, "has no triangles (" + std::to_string(mesh.vertices.size()) +
                                    " vertices); a body needs a surface");
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      throwMeshError(mesh.source, "vertex " + std::to_string(i) + " = " +
                                      mesh_detail::formatPoint(v.x, v.y, v.z) + " is not finite");
    }
  }
  const std::size_t vertexCount = mesh.vertices.size();
  bool anyArea = false;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::uint32_t index : tri) {
      if (index >= vertexCount) {
        throwMeshError(mesh.source, "triangle " + std::to_string(t) + " has vertex index " +
                                        std::to_string(index) + ", but the mesh has " +
                                        std::to_string(vertexCount) + " vertices");
      }
    }
    anyArea = anyArea || mesh_detail::hasArea(mesh_detail::toEigen(mesh.vertices[tri[0]]),
                                              mesh_detail::toEigen(mesh.vertices[tri[1]]),
                                              mesh_detail::toEigen(mesh.vertices[tri[2]]));
  }
  if (!anyArea) {
    throwMeshError(mesh.source, "all " + std::to_string(mesh.triangles.size()) +
                                    " triangles have zero area (collinear or repeated corners)");
  }
}

}  // namespace sandphys
