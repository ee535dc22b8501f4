#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/validation.h"
#include "sandphys/body.h"

namespace sandphys {
namespace {

void requireFiniteCentres(const std::vector<Vec3>& centres) {
  detail::require(!centres.empty(), "particle count", 0, "a template needs at least one particle");
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const Vec3& c = centres[i];
    detail::require(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z),
                    "particle centre " + std::to_string(i),
                    std::isfinite(c.x) ? (std::isfinite(c.y) ? c.z : c.y) : c.x, "must be finite");
  }
}

// The part both template builders share: rotate the centres into the principal frame of
// `inertia` (about `com`, in the centres' frame) and store mass and principal moments.
ParticleTemplate principalTemplate(const std::vector<Vec3>& centres, const Eigen::Vector3d& com,
                                   const Eigen::Matrix3d& inertia, double mass) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();       // columns: principal axes in the given frame
  if (axes.determinant() < 0.0) axes.col(2) *= -1.0;  // keep it a rotation
  // An isotropic body (the tetrahedral granule, a cube, a sphere) is principal in any frame: keep
  // the given one so that its orientation needs no conversion on read-back.
  const Eigen::Vector3d moments = solver.eigenvalues();
  if (moments.maxCoeff() - moments.minCoeff() <= 1e-6 * moments.maxCoeff()) {
    axes.setIdentity();
  }

  ParticleTemplate t;
  t.mass = static_cast<float>(mass);
  t.principalInertia = {float(moments(0)), float(moments(1)), float(moments(2))};
  Eigen::Quaterniond q(axes);
  q.normalize();
  t.principalRotation = {float(q.w()), float(q.x()), float(q.y()), float(q.z())};
  double bound = 0.0;
  t.offsets.reserve(centres.size());
  for (const Vec3& c : centres) {
    Eigen::Vector3d local = axes.transpose() * (Eigen::Vector3d(c.x, c.y, c.z) - com);
    t.offsets.push_back({float(local.x()), float(local.y()), float(local.z())});
    bound = std::max(bound, local.norm());
  }
  t.boundingRadius = static_cast<float>(bound);
  return t;
}

}  // namespace

ParticleTemplate makeParticleTemplate(const std::vector<Vec3>& centres, float particleDiameter,
                                      float density, float mass) {
  detail::requirePositive("particleDiameter", particleDiameter, "(m)");
  detail::requireNonNegative("mass", mass, "(kg)");
  if (mass == 0.0f) detail::requirePositive("density", density, "(kg/m^3)");
  requireFiniteCentres(centres);

  const double r = 0.5 * particleDiameter;
  const double sphereMass = mass > 0.0f ? double(mass) / double(centres.size())
                                        : density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (const Vec3& c : centres) com += Eigen::Vector3d(c.x, c.y, c.z);
  com /= double(centres.size());

  // Solid spheres plus parallel-axis terms: I = Σ (2/5 m r² 1 + m (|p|² 1 - p pᵀ)).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (const Vec3& c : centres) {
    Eigen::Vector3d p = Eigen::Vector3d(c.x, c.y, c.z) - com;
    inertia += sphereMass * (0.4 * r * r * Eigen::Matrix3d::Identity() +
                             (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose()));
  }
  return principalTemplate(centres, com, inertia, sphereMass * double(centres.size()));
}

ParticleTemplate makeBodyTemplate(const std::vector<Vec3>& centres,
                                  const MassProperties& massProperties) {
  requireFiniteCentres(centres);
  detail::requirePositive("MassProperties.mass", massProperties.mass, "(kg)");
  Eigen::Vector3d com;
  Eigen::Matrix3d inertia;
  for (int i = 0; i < 3; ++i) {
    com(i) = massProperties.centreOfMass[i];
    detail::requireFinite("MassProperties.centreOfMass[" + std::to_string(i) + "]", com(i));
    for (int j = 0; j < 3; ++j) {
      inertia(i, j) = massProperties.inertia[i][j];
      detail::requireFinite(
          "MassProperties.inertia[" + std::to_string(i) + "][" + std::to_string(j) + "]",
          inertia(i, j));
    }
  }
  const double scale = inertia.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      // Relative: the tensor typically comes out of a sum in double and may carry rounding.
      detail::require(
          std::abs(inertia(i, j) - inertia(j, i)) <= 1e-9 * scale,
          "MassProperties.inertia[" + std::to_string(i) + "][" + std::to_string(j) + "]",
          inertia(i, j),
          "must equal inertia[" + std::to_string(j) + "][" + std::to_string(i) +
              "] = " + detail::formatValue(inertia(j, i)) + " (a symmetric tensor)");
    }
  }
  inertia = 0.5 * (inertia + inertia.transpose());
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly).eigenvalues();
  detail::require(moments(0) > 0.0, "MassProperties.inertia: smallest principal moment", moments(0),
                  "must be > 0 (kg m^2): the tensor must be positive definite");
  // Every mass distribution has I_max <= I_a + I_b; a flat plate reaches equality, so allow the
  // rounding of a double sum.
  detail::require(moments(2) <= (moments(0) + moments(1)) * (1.0 + 1e-9),
                  "MassProperties.inertia: largest principal moment", moments(2),
                  "must be <= the sum of the other two, " +
                      detail::formatValue(moments(0) + moments(1)) +
                      " (kg m^2), or no mass distribution has it");
  return principalTemplate(centres, com, inertia, massProperties.mass);
}

ParticleTemplate tetrahedronTemplate(float particleDiameter, float density) {
  // Alternate corners of a cube of side a have edge a·√2; edge = d gives a = d/√2.
  const float h = particleDiameter / (2.0f * std::numbers::sqrt2_v<float>);
  return makeParticleTemplate({{h, h, h}, {h, -h, -h}, {-h, h, -h}, {-h, -h, h}}, particleDiameter,
                              density);
}

}  // namespace sandphys
