#include <algorithm>
#include <cmath>

#include "core/validation.h"
#include "mesh/mesh_checks.h"
#include "mesh/samplers.h"

namespace sandphys::mesh_detail {

void throwTooManyParticles(const std::string& source, double spacing, std::size_t maxParticles,
                           double estimate) {
  std::string need = estimate > 0.0 ? "about " + detail::formatValue(std::round(estimate))
                                    : "more than " + std::to_string(maxParticles);
  throw CapacityExceeded(
      meshName(source) + ": sampling it at spacing " + detail::formatValue(spacing) + " m needs " +
      need + " particles, but MeshSampling.maxParticles = " + std::to_string(maxParticles) +
      " (raise the limit, or sample coarser: larger spacing or diameter)");
}

PointGrid sampleSurface(const TriangleMesh& mesh, double spacing, std::size_t maxParticles) {
  // Subdivisions per triangle first, so that a hopeless request fails before any allocation. A
  // closed surface of F lattice triangles has about F/2 corners once shared ones are welded, so
  // Σ n²/2 estimates the count from below and never refuses a mesh that would fit.
  std::vector<std::uint32_t> divisions(mesh.triangles.size(), 0);
  double estimate = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    const Eigen::Vector3d b = toEigen(mesh.vertices[tri[1]]);
    const Eigen::Vector3d c = toEigen(mesh.vertices[tri[2]]);
    // A triangle without area adds no surface; its edges belong to its neighbours as well.
    if (!hasArea(a, b, c)) continue;
    const double longest =
        std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const double n = std::max(1.0, std::ceil(longest / spacing));
    estimate += 0.5 * n * n;
    // Capped so that the cast stays defined; such a triangle fails the estimate below anyway.
    divisions[t] = std::uint32_t(std::min(n, 1e9));
  }
  if (estimate > double(maxParticles)) {
    throwTooManyParticles(mesh.source, spacing, maxParticles, estimate);
  }

  // Points on an edge that two triangles share come out of both, equal up to rounding; points
  // of different meshes never come closer than the spacing allows. A thousandth of the spacing
  // tells the two apart.
  const double weld = 1e-3 * spacing;
  PointGrid grid(0.5 * spacing);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t n = divisions[t];
    if (n == 0) continue;
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    const Eigen::Vector3d b = toEigen(mesh.vertices[tri[1]]);
    const Eigen::Vector3d c = toEigen(mesh.vertices[tri[2]]);
    for (std::uint32_t i = 0; i <= n; ++i) {
      for (std::uint32_t j = 0; j <= n - i; ++j) {
        const std::uint32_t k = n - i - j;
        const Eigen::Vector3d p = (double(i) * a + double(j) * b + double(k) * c) / double(n);
        if (grid.addUnlessNear(p, weld) && grid.points().size() > maxParticles) {
          throwTooManyParticles(mesh.source, spacing, maxParticles, 0.0);
        }
      }
    }
  }
  return grid;
}

}  // namespace sandphys::mesh_detail
