#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/log.h"
#include "core/validation.h"
#include "mesh/mesh_checks.h"
#include "mesh/samplers.h"
#include "sandphys/mesh.h"

namespace sandphys {
namespace {

// The mass properties a template carries, back in the frame of its particle centres: the
// centre of mass is the mean of the centres (makeParticleTemplate puts it there) and the tensor
// is R diag(I) Rᵀ.
MassProperties massPropertiesOf(const ParticleTemplate& shape, const std::vector<Vec3>& centres) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Vec3& c : centres) mean += mesh_detail::toEigen(c);
  mean /= double(centres.size());
  const Quat& q = shape.principalRotation;
  const Eigen::Matrix3d axes = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
  const Eigen::Matrix3d inertia =
      axes * mesh_detail::toEigen(shape.principalInertia).asDiagonal() * axes.transpose();
  MassProperties result;
  result.mass = shape.mass;
  for (int i = 0; i < 3; ++i) {
    result.centreOfMass[i] = mean(i);
    for (int j = 0; j < 3; ++j) result.inertia[i][j] = inertia(i, j);
  }
  return result;
}

std::vector<Vec3> toFloat(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back({float(p.x()), float(p.y()), float(p.z())});
  return out;
}

}  // namespace

SampledMesh sampleMesh(const TriangleMesh& mesh, float particleDiameter,
                       const MeshSampling& options) {
  detail::requirePositive("particleDiameter", particleDiameter, "(m)");
  detail::requireNonNegative("MeshSampling.spacing", options.spacing, "(m)");
  const double spacing =
      options.spacing > 0.0f ? options.spacing : double(kDefaultMeshSpacing) * particleDiameter;
  detail::require(spacing < std::numbers::sqrt3 * particleDiameter, "MeshSampling.spacing",
                  options.spacing,
                  "must be < sqrt(3) * particleDiameter = " +
                      detail::formatValue(std::numbers::sqrt3 * particleDiameter) +
                      " m, or grains of that diameter pass between the samples");
  detail::requireNonNegative("MeshSampling.mass", options.mass, "(kg)");
  if (options.mass == 0.0f)
    detail::requirePositive("MeshSampling.density", options.density, "(kg/m^3)");
  detail::require(options.maxParticles > 0, "MeshSampling.maxParticles", options.maxParticles,
                  "must be > 0");

  const MeshEdges edges = analyseEdges(mesh);  // validates the mesh
  SampledMesh result;
  result.closed = edges.closed();
  result.surfaceArea = surfaceArea(mesh);
  if (options.fillVolume && !result.closed) {
    mesh_detail::throwMeshError(
        mesh.source, "MeshSampling.fillVolume needs a closed mesh, but this one has " +
                         std::to_string(edges.openEdges) + " open and " +
                         std::to_string(edges.misorientedEdges) + " misoriented edges of " +
                         std::to_string(edges.edges));
  }

  const mesh_detail::PointGrid surface =
      mesh_detail::sampleSurface(mesh, spacing, options.maxParticles);
  result.centres = toFloat(surface.points());
  result.surfaceParticles = result.centres.size();
  if (options.fillVolume) {
    const std::vector<Vec3> interior =
        toFloat(mesh_detail::sampleInterior(mesh, spacing, surface, options.maxParticles));
    result.centres.insert(result.centres.end(), interior.begin(), interior.end());
  }

  if (result.closed) {
    // mass > 0 overrides the density: scale the solid of density 1 to it.
    const double density = options.mass > 0.0f ? 1.0 : double(options.density);
    const SolidProperties solid = solidProperties(mesh, density);
    result.volume = solid.volume;
    result.massProperties = solid.massProperties;
    if (options.mass > 0.0f) {
      const double scale = options.mass / solid.massProperties.mass;
      result.massProperties.mass = options.mass;
      for (auto& row : result.massProperties.inertia)
        for (double& value : row) value *= scale;
    }
    if (solid.woundInward) {
      result.warnings.push_back(
          mesh_detail::meshName(mesh) +
          ": its triangles are wound inward (clockwise seen from outside); sampled as the solid "
          "they enclose");
    }
    result.shape = makeBodyTemplate(result.centres, result.massProperties);
  } else {
    result.shape =
        makeParticleTemplate(result.centres, particleDiameter, options.density, options.mass);
    result.massProperties = massPropertiesOf(result.shape, result.centres);
    const std::string massRule =
        options.mass > 0.0f
            ? "scaled to MeshSampling.mass = " + detail::formatValue(options.mass) + " kg"
            : "each of density " + detail::formatValue(options.density) +
                  " kg/m^3, a thin shell of " + detail::formatValue(result.shape.mass) +
                  " kg, far lighter than a solid of that outline";
    result.warnings.push_back(
        mesh_detail::meshName(mesh) + ": not closed (" + std::to_string(edges.openEdges) +
        " open and " + std::to_string(edges.misorientedEdges) + " misoriented edges of " +
        std::to_string(edges.edges) +
        "), so it bounds no solid: the body's mass properties are those of its " +
        std::to_string(result.centres.size()) + " particles as solid spheres of diameter " +
        detail::formatValue(particleDiameter) + " m, " + massRule);
  }
  result.shape.surfaceSpacing = float(spacing);
  if (result.centres.size() > kLargeBodyWarningParticles) {
    result.warnings.push_back(
        mesh_detail::meshName(mesh) + ": " + std::to_string(result.centres.size()) +
        " particles (more than " + std::to_string(kLargeBodyWarningParticles) +
        "): every substep one workgroup (one CPU core on llvmpipe) sums and moves them all, so "
        "the body may cost more than the sand around it; a larger MeshSampling.spacing (below " +
        detail::formatValue(std::numbers::sqrt3 * particleDiameter) +
        " m), fillVolume off, a larger particle diameter or a smaller mesh lowers it");
  }
  for (const std::string& warning : result.warnings) {
    detail::log(LogLevel::Warning, warning);
  }
  return result;
}

}  // namespace sandphys
