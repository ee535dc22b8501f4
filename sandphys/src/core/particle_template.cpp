#include <Eigen/Dense>

#include <cmath>
#include <numbers>

#include "core/validation.h"
#include "sandphys/body.h"

namespace sandphys {

ParticleTemplate makeParticleTemplate(const std::vector<Vec3>& centres, float particleDiameter,
                                      float density, float mass) {
  detail::requirePositive("particleDiameter", particleDiameter, "(m)");
  detail::requireNonNegative("mass", mass, "(kg)");
  if (mass == 0.0f) detail::requirePositive("density", density, "(kg/m^3)");
  detail::require(!centres.empty(), "particle count", 0, "a template needs at least one particle");

  const double r = 0.5 * particleDiameter;
  const double sphereMass = mass > 0.0f ? double(mass) / double(centres.size())
                                        : density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const Vec3& c = centres[i];
    detail::require(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z),
                    "particle centre " + std::to_string(i),
                    std::isfinite(c.x) ? (std::isfinite(c.y) ? c.z : c.y) : c.x, "must be finite");
    com += Eigen::Vector3d(c.x, c.y, c.z);
  }
  com /= double(centres.size());

  // Solid spheres plus parallel-axis terms: I = Σ (2/5 m r² 1 + m (|p|² 1 - p pᵀ)).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (const Vec3& c : centres) {
    Eigen::Vector3d p = Eigen::Vector3d(c.x, c.y, c.z) - com;
    inertia += sphereMass * (0.4 * r * r * Eigen::Matrix3d::Identity() +
                             (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose()));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();       // columns: principal axes in the given frame
  if (axes.determinant() < 0.0) axes.col(2) *= -1.0;  // keep it a rotation
  // An isotropic body (the tetrahedral granule) is principal in any frame: keep the given one so
  // that its orientation needs no conversion on read-back.
  const Eigen::Vector3d moments = solver.eigenvalues();
  if (moments.maxCoeff() - moments.minCoeff() <= 1e-6 * moments.maxCoeff()) {
    axes.setIdentity();
  }

  ParticleTemplate t;
  t.mass = static_cast<float>(sphereMass * double(centres.size()));
  t.principalInertia = {float(solver.eigenvalues()(0)), float(solver.eigenvalues()(1)),
                        float(solver.eigenvalues()(2))};
  Eigen::Quaterniond q(axes);
  q.normalize();
  t.principalRotation = {float(q.w()), float(q.x()), float(q.y()), float(q.z())};
  double bound = 0.0;
  for (const Vec3& c : centres) {
    Eigen::Vector3d local = axes.transpose() * (Eigen::Vector3d(c.x, c.y, c.z) - com);
    t.offsets.push_back({float(local.x()), float(local.y()), float(local.z())});
    bound = std::max(bound, local.norm());
  }
  t.boundingRadius = static_cast<float>(bound);
  return t;
}

ParticleTemplate tetrahedronTemplate(float particleDiameter, float density) {
  // Alternate corners of a cube of side a have edge a·√2; edge = d gives a = d/√2.
  const float h = particleDiameter / (2.0f * std::numbers::sqrt2_v<float>);
  return makeParticleTemplate({{h, h, h}, {h, -h, -h}, {-h, h, -h}, {-h, -h, h}}, particleDiameter,
                              density);
}

}  // namespace sandphys
