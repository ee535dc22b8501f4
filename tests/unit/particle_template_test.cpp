// Templates: mass and inertia computed (with Eigen) from particle centres, in the principal frame.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <cmath>
#include <numbers>

namespace sandphys {
namespace {

double length(Vec3 v) {
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
    EXPECT_NEAR(length(t.offsets[i]), circumradius, 1e-6);
    for (std::size_t j = i + 1; j < 4; ++j) {
      Vec3 a = t.offsets[i], b = t.offsets[j];
      EXPECT_NEAR(length({a.x - b.x, a.y - b.y, a.z - b.z}), d, 1e-6) << "edge " << i << j;
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

}  // namespace
}  // namespace sandphys
