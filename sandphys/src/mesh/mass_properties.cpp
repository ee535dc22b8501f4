#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/validation.h"
#include "mesh/mesh_checks.h"
#include "sandphys/mesh.h"

namespace sandphys {

using mesh_detail::boundsOfTriangles;
using mesh_detail::toEigen;

double surfaceArea(const TriangleMesh& mesh) {
  validateMesh(mesh);
  double twiceArea = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    twiceArea +=
        (toEigen(mesh.vertices[tri[1]]) - a).cross(toEigen(mesh.vertices[tri[2]]) - a).norm();
  }
  return 0.5 * twiceArea;
}

SolidProperties solidProperties(const TriangleMesh& mesh, double density) {
  detail::requirePositive("density", density, "(kg/m^3)");
  const MeshEdges edges = analyseEdges(mesh);
  if (!edges.closed()) {
    mesh_detail::throwMeshError(
        mesh.source, "is not closed (" + std::to_string(edges.openEdges) + " open and " +
                         std::to_string(edges.misorientedEdges) + " misoriented edges of " +
                         std::to_string(edges.edges) + "), so it bounds no solid");
  }

  // The tetrahedra fan out from the centre of the bounding box rather than from the origin: a
  // mesh modelled far from its file's origin would otherwise sum large terms of opposite sign.
  const auto [lo, hi] = boundsOfTriangles(mesh);
  const Eigen::Vector3d origin = 0.5 * (lo + hi);

  // Divergence theorem over signed tetrahedra (origin, a, b, c), det = a · (b × c) = 6 V_t:
  //   ∫ dV     = det / 6
  //   ∫ x dV   = det / 24 · (a + b + c)
  //   ∫ x xᵀ dV = det / 120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ),  s = a + b + c
  // (the moments of a tetrahedron with one corner at the origin). Summed over a closed surface,
  // the parts outside the solid cancel and the sums are the solid's.
  double volume = 0.0;
  double unsignedVolume = 0.0;  // Σ |V_t|: the scale of the rounding in `volume`
  Eigen::Vector3d firstMoment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero();
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]) - origin;
    const Eigen::Vector3d b = toEigen(mesh.vertices[tri[1]]) - origin;
    const Eigen::Vector3d c = toEigen(mesh.vertices[tri[2]]) - origin;
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d s = a + b + c;
    volume += det / 6.0;
    unsignedVolume += std::abs(det) / 6.0;
    firstMoment += det / 24.0 * s;
    secondMoment += det / 120.0 *
                    (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }

  SolidProperties solid;
  if (volume < 0.0) {
    // Inward winding negates every signed tetrahedron alike.
    solid.woundInward = true;
    volume = -volume;
    firstMoment = -firstMoment;
    secondMoment = -secondMoment;
  }
  // What is left after the tetrahedra cancel must stand out of their rounding.
  if (!(volume > 1e-9 * unsignedVolume)) {
    mesh_detail::throwMeshError(mesh.source,
                                "is closed but encloses no volume (" + detail::formatValue(volume) +
                                    " m^3): a flat or doubled-over surface cannot be a solid");
  }

  const Eigen::Vector3d centre = firstMoment / volume;  // relative to `origin`
  // Second moment about the centre of mass (parallel-axis theorem), then I = tr(C) 1 - C.
  const Eigen::Matrix3d central = secondMoment - volume * centre * centre.transpose();
  const Eigen::Matrix3d inertia =
      density * (central.trace() * Eigen::Matrix3d::Identity() - central);

  solid.volume = volume;
  solid.massProperties.mass = density * volume;
  for (int i = 0; i < 3; ++i) {
    solid.massProperties.centreOfMass[i] = origin(i) + centre(i);
    for (int j = 0; j < 3; ++j) {
      // The tensor is symmetric in exact arithmetic; average away the rounding.
      solid.massProperties.inertia[i][j] = 0.5 * (inertia(i, j) + inertia(j, i));
    }
  }
  return solid;
}

}  // namespace sandphys
