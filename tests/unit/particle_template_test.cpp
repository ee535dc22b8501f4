// Templates: mass and inertia computed (with Eigen) from particle centres, in the principal frame.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace sandphys {
namespace {

// In double, so that the 1e-6 m checks measure the template, not the rounding of a float norm.
double norm(Vec3 v) {
  return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
}

TEST(ParticleTemplate, TetrahedronHasTouchingParticlesAndIsotropicInertia) {
  const float d = 0.02f, density = 2600.0f;
  ParticleTemplate t = tetrahedronTemplate(d, density);
  ASSERT_EQ(t.offsets.size(), 4u);
  const double m = density * std::numbers::pi * d * d * d / 6.0;
  EXPECT_NEAR(t.mass, 4.0 * m, 1e-6 * m);
  const double circumradius = d * std::sqrt(6.0) / 4.0;
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(norm(t.offsets[i]), circumradius, 1e-6);
    for (std::size_t j = i + 1; j < 4; ++j) {
      Vec3 a = t.offsets[i], b = t.offsets[j];
      EXPECT_NEAR(norm(a - b), d, 1e-6) << "edge " << i << j;
    }
  }
  // Spheres: 4 (2/5 m r²) plus point masses at the corners: Σ m (|p|² - p_x²) = 8/3 m R².
  const double r = d / 2.0;
  const double inertia = 4.0 * 0.4 * m * r * r + 8.0 / 3.0 * m * circumradius * circumradius;
  EXPECT_NEAR(t.principalInertia.x, inertia, 1e-5 * inertia);
  EXPECT_NEAR(t.principalInertia.y, inertia, 1e-5 * inertia);
  EXPECT_NEAR(t.principalInertia.z, inertia, 1e-5 * inertia);
  EXPECT_EQ(t.principalRotation.w, 1.0f);  // isotropic: keeps the given frame
  EXPECT_NEAR(t.boundingRadius, circumradius, 1e-6);
}

TEST(ParticleTemplate, DumbbellIsCentredAndDiagonalised) {
  // Two particles along a tilted axis, off the origin: the template moves the centre of mass to
  // the origin and rotates the long axis onto a principal axis.
  const float d = 0.02f;
  const double s = 0.05;
  Vec3 a{1.0f, 2.0f, 3.0f};
  Vec3 b{float(1.0 + s / std::sqrt(2.0)), float(2.0 + s / std::sqrt(2.0)), 3.0f};
  ParticleTemplate t = makeParticleTemplate({a, b}, d, 1000.0f);
  const double m = 1000.0 * std::numbers::pi * d * d * d / 6.0;
  const double sphere = 0.4 * m * (d / 2.0) * (d / 2.0);
  const double across = 2.0 * sphere + 2.0 * m * (s / 2.0) * (s / 2.0);
  // Eigen sorts the moments ascending: the axis along the dumbbell first.
  EXPECT_NEAR(t.principalInertia.x, 2.0 * sphere, 1e-4 * across);
  EXPECT_NEAR(t.principalInertia.y, across, 1e-4 * across);
  EXPECT_NEAR(t.principalInertia.z, across, 1e-4 * across);
  EXPECT_NEAR(t.offsets[0].x + t.offsets[1].x, 0.0, 1e-6);
  EXPECT_NEAR(std::abs(t.offsets[0].x), s / 2.0, 1e-6);
  EXPECT_NEAR(t.offsets[0].y, 0.0, 1e-6);
  EXPECT_NEAR(t.offsets[0].z, 0.0, 1e-6);
}

TEST(ParticleTemplate, GivenMassScalesInertia) {
  ParticleTemplate t = makeParticleTemplate({{0, 0, 0}, {0.02f, 0, 0}}, 0.02f, 0.0f, 2.0f);
  EXPECT_FLOAT_EQ(t.mass, 2.0f);
  EXPECT_NEAR(t.principalInertia.y, 2.0 * (0.4 * 0.01 * 0.01 + 0.01 * 0.01), 1e-8);
}

TEST(ParticleTemplate, BadInputIsRefused) {
  EXPECT_THROW(makeParticleTemplate({}, 0.02f, 1000.0f), InvalidArgument);
  EXPECT_THROW(makeParticleTemplate({{0, std::nanf(""), 0}}, 0.02f, 1000.0f), InvalidArgument);
  EXPECT_THROW(makeParticleTemplate({{0, 0, 0}}, -1.0f, 1000.0f), InvalidArgument);
  EXPECT_THROW(makeParticleTemplate({{0, 0, 0}}, 0.02f, 0.0f), InvalidArgument);
}

// A solid box's tensor, turned by a rotation about z and given to makeBodyTemplate with two
// particles: the moments and centre of mass come from the tensor, not from the particles.
TEST(BodyTemplate, TakesMassAndInertiaAsGiven) {
  const double angle = 0.5, c = std::cos(angle), s = std::sin(angle);
  const double ix = 1.0, iy = 3.0, iz = 3.5;  // diagonal in a frame turned by `angle` about z
  MassProperties props;
  props.mass = 7.0;
  props.centreOfMass = {1.0, 2.0, 3.0};
  props.inertia = {{{c * c * ix + s * s * iy, c * s * (ix - iy), 0.0},
                    {c * s * (ix - iy), s * s * ix + c * c * iy, 0.0},
                    {0.0, 0.0, iz}}};
  // One particle on the long axis (x turned by `angle`) 0.1 m from the centre of mass, one at it.
  const Vec3 along{float(1.0 + 0.1 * c), float(2.0 + 0.1 * s), 3.0f};
  ParticleTemplate t = makeBodyTemplate({along, {1.0f, 2.0f, 3.0f}}, props);
  EXPECT_FLOAT_EQ(t.mass, 7.0f);
  EXPECT_NEAR(t.principalInertia.x, ix, 1e-6);
  EXPECT_NEAR(t.principalInertia.y, iy, 1e-6);
  EXPECT_NEAR(t.principalInertia.z, iz, 1e-6);
  // In the principal frame the first particle lies on the axis of the smallest moment.
  EXPECT_NEAR(std::abs(t.offsets[0].x), 0.1, 1e-6);
  EXPECT_NEAR(t.offsets[0].y, 0.0, 1e-6);
  EXPECT_NEAR(t.offsets[0].z, 0.0, 1e-6);
  EXPECT_NEAR(norm(t.offsets[1]), 0.0, 1e-6);
  EXPECT_NEAR(t.boundingRadius, 0.1, 1e-6);
  // The rotation takes the principal axes back to the given frame: x onto the turned long axis,
  // z onto z (each up to its sign, which an eigenvector does not have).
  const Eigen::Quaterniond q(t.principalRotation.w, t.principalRotation.x, t.principalRotation.y,
                             t.principalRotation.z);
  EXPECT_NEAR(std::abs((q * Eigen::Vector3d::UnitX()).dot(Eigen::Vector3d(c, s, 0.0))), 1.0, 1e-6);
  EXPECT_NEAR(std::abs((q * Eigen::Vector3d::UnitZ()).z()), 1.0, 1e-6);
}

TEST(BodyTemplate, IsotropicTensorKeepsTheGivenFrame) {
  MassProperties props;
  props.mass = 2.0;
  props.inertia = {{{0.5, 0.0, 0.0}, {0.0, 0.5, 0.0}, {0.0, 0.0, 0.5}}};
  ParticleTemplate t = makeBodyTemplate({{0.1f, 0.2f, 0.3f}}, props);
  EXPECT_EQ(t.principalRotation.w, 1.0f);
  EXPECT_FLOAT_EQ(t.offsets[0].y, 0.2f);
}

TEST(BodyTemplate, UnphysicalMassPropertiesAreRefused) {
  MassProperties good;
  good.mass = 1.0;
  good.inertia = {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  const std::vector<Vec3> one{{0, 0, 0}};
  EXPECT_NO_THROW(makeBodyTemplate(one, good));
  EXPECT_THROW(makeBodyTemplate({}, good), InvalidArgument);
  EXPECT_THROW(makeBodyTemplate({{0, std::nanf(""), 0}}, good), InvalidArgument);

  auto refused = [&](MassProperties props, const std::string& field) {
    try {
      makeBodyTemplate(one, props);
      ADD_FAILURE() << "accepted, expected an error naming " << field;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  MassProperties p = good;
  p.mass = 0.0;
  refused(p, "MassProperties.mass");
  p = good;
  p.centreOfMass[1] = std::nan("");
  refused(p, "MassProperties.centreOfMass[1]");
  p = good;
  p.inertia[0][2] = 0.1;  // not symmetric
  refused(p, "MassProperties.inertia[0][2]");
  p = good;
  p.inertia[2][2] = -1.0;  // not positive definite
  refused(p, "smallest principal moment");
  p = good;
  p.inertia[2][2] = 2.5;  // 2.5 > 1 + 1: no mass distribution has it
  refused(p, "largest principal moment");
  p = good;
  p.inertia[1][1] = std::numeric_limits<double>::infinity();
  refused(p, "MassProperties.inertia[1][1]");
}

}  // namespace
}  // namespace sandphys
