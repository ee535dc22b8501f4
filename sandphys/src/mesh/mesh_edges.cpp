#include <cstdint>
#include <unordered_map>

#include "mesh/mesh_checks.h"
#include "sandphys/mesh.h"

namespace sandphys {

MeshEdges analyseEdges(const TriangleMesh& mesh) {
  validateMesh(mesh);
  const std::vector<std::uint32_t> ids = mesh_detail::firstVertexAtPosition(mesh);
  struct Uses {
    std::uint32_t total = 0;
    std::int64_t balance = 0;  // uses from the lower id to the higher minus the other way
  };
  std::unordered_map<std::uint64_t, Uses> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const auto& tri : mesh.triangles) {
    const std::uint32_t v[3] = {ids[tri[0]], ids[tri[1]], ids[tri[2]]};
    // A triangle with a repeated corner bounds nothing: its two real edges cancel each other.
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t from = v[k], to = v[(k + 1) % 3];
      const std::uint64_t key =
          from < to ? (std::uint64_t(from) << 32 | to) : (std::uint64_t(to) << 32 | from);
      Uses& uses = edges[key];
      ++uses.total;
      uses.balance += from < to ? 1 : -1;
    }
  }
  MeshEdges result;
  result.edges = edges.size();
  for (const auto& [key, uses] : edges) {
    if (uses.total % 2 == 1) {
      ++result.openEdges;
    } else if (uses.balance != 0) {
      ++result.misorientedEdges;
    }
  }
  return result;
}

}  // namespace sandphys
