// Mass properties of closed meshes (divergence theorem) and the bodies sampleMesh builds from them.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "mesh/mesh_shapes.h"

namespace sandphys {
namespace {

using mesh_testing::namedBox;
using mesh_testing::namedIcosphere;
using mesh_testing::toEigen;

Eigen::Matrix3d toMatrix(const std::array<std::array<double, 3>, 3>& m) {
  Eigen::Matrix3d out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out(i, j) = m[i][j];
  return out;
}

Eigen::Vector3d toVector(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

// Largest entry of |a - b| relative to the largest entry of |b|.
double relativeError(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// The box's closed form, from the float corners the mesh really has.
Eigen::Matrix3d boxInertia(double mass, Eigen::Vector3d size) {
  const Eigen::Vector3d s2 = size.cwiseProduct(size);
  return mass / 12.0 *
         Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal();
}

TEST(MassProperties, OffsetBoxIsExact) {
  const Vec3 lo{1.0f, 2.0f, 3.0f}, hi{1.3f, 2.2f, 3.1f};
  const double density = 2600.0;
  const SolidProperties solid = solidProperties(boxMesh(lo, hi), density);
  const Eigen::Vector3d size = toEigen(hi) - toEigen(lo);
  const double volume = size.prod();
  EXPECT_NEAR(solid.volume, volume, 1e-12 * volume);
  EXPECT_FALSE(solid.woundInward);
  EXPECT_NEAR(solid.massProperties.mass, density * volume, 1e-9 * density * volume);
  const Eigen::Vector3d centre = 0.5 * (toEigen(lo) + toEigen(hi));
  EXPECT_LT((toVector(solid.massProperties.centreOfMass) - centre).norm(), 1e-12);
  const Eigen::Matrix3d expected = boxInertia(density * volume, size);
  const double error = relativeError(toMatrix(solid.massProperties.inertia), expected);
  std::printf("offset box: inertia error %.3g (relative to the largest moment)\n", error);
  EXPECT_LT(error, 1e-10);
}

TEST(MassProperties, RotatedBoxHasTheRotatedTensor) {
  // Off-diagonal terms: the box's tensor in a frame where it is not diagonal.
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d size(0.4, 0.2, 0.1);
  const TriangleMesh box = mesh_testing::transformed(
      boxMesh({-0.2f, -0.1f, -0.05f}, {0.2f, 0.1f, 0.05f}), rotation, {0.5, -1.0, 2.0});
  const SolidProperties solid = solidProperties(box, 1000.0);
  const double mass = 1000.0 * size.prod();
  const Eigen::Matrix3d expected = rotation * boxInertia(mass, size) * rotation.transpose();
  const double error = relativeError(toMatrix(solid.massProperties.inertia), expected);
  std::printf("rotated box: inertia error %.3g (float corners)\n", error);
  EXPECT_LT(error, 1e-6);  // the corners were rounded to float after rotating
  EXPECT_NEAR(expected(0, 1), toMatrix(solid.massProperties.inertia)(0, 1), 1e-6 * expected.norm());
  EXPECT_GT(std::abs(expected(0, 1)), 0.05 * expected.norm());
  EXPECT_LT((toVector(solid.massProperties.centreOfMass) - Eigen::Vector3d(0.5, -1.0, 2.0)).norm(),
            1e-6);
}

// The polyhedron's own value by another route: a star-shaped mesh is a union of tetrahedra
// (centre, a, b, c), and the 4-point Keast rule integrates quadratics over each one exactly.
Eigen::Matrix3d starPolyhedronInertia(const TriangleMesh& mesh, Eigen::Vector3d centre,
                                      double density, double& volume) {
  const double alpha = 0.5854101966249685, beta = 0.1381966011250105;
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  volume = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d v[4] = {centre, toEigen(mesh.vertices[tri[0]]),
                                  toEigen(mesh.vertices[tri[1]]), toEigen(mesh.vertices[tri[2]])};
    const double tetVolume = (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) / 6.0;
    volume += tetVolume;
    for (int q = 0; q < 4; ++q) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) p += (k == q ? alpha : beta) * v[k];
      const Eigen::Vector3d r = p - centre;
      second +=
          tetVolume / 4.0 * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
  }
  return density * second;
}

TEST(MassProperties, SphereMatchesThePolyhedronAndTheIdealSphere) {
  const double radius = 0.1, density = 2600.0;
  const Vec3 centre{0.2f, 0.3f, -0.4f};
  const TriangleMesh sphere = icosphereMesh(radius, 4, centre);
  const SolidProperties solid = solidProperties(sphere, density);

  double polyVolume = 0.0;
  const Eigen::Matrix3d polyInertia =
      starPolyhedronInertia(sphere, toEigen(centre), density, polyVolume);
  EXPECT_NEAR(solid.volume, polyVolume, 1e-12);
  const double polyError = relativeError(toMatrix(solid.massProperties.inertia), polyInertia);
  EXPECT_LT(polyError, 1e-9);
  // Symmetric: the centre of mass is the centre.
  EXPECT_LT((toVector(solid.massProperties.centreOfMass) - toEigen(centre)).norm(), 1e-8);

  const double idealVolume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  const double idealMoment = 0.4 * density * idealVolume * radius * radius;
  const Eigen::Matrix3d inertia = toMatrix(solid.massProperties.inertia);
  const double volumeError = solid.volume / idealVolume - 1.0;
  const double momentError = inertia.diagonal().maxCoeff() / idealMoment - 1.0;
  std::printf(
      "icosphere (5120 triangles): volume %+.3f%%, moment %+.3f%% against the ideal sphere; "
      "%.2g against the polyhedron by quadrature\n",
      100 * volumeError, 100 * momentError, polyError);
  EXPECT_LT(std::abs(volumeError), 0.02);
  EXPECT_LT(std::abs(momentError), 0.02);
  // Inscribed: a little smaller than the sphere, never larger.
  EXPECT_LT(volumeError, 0.0);
  // Icosahedral symmetry makes the tensor isotropic.
  EXPECT_LT(relativeError(inertia, inertia.diagonal().mean() * Eigen::Matrix3d::Identity()), 1e-6);

  // The sampled body carries the polyhedron's mass and moments (in float), not its particles'.
  const SampledMesh sampled = sampleMesh(sphere, 0.02f, {.density = float(density)});
  EXPECT_NEAR(sampled.shape.mass, density * polyVolume, 1e-6 * density * polyVolume);
  const double polyMoment = polyInertia.diagonal().mean();
  for (float moment : {sampled.shape.principalInertia.x, sampled.shape.principalInertia.y,
                       sampled.shape.principalInertia.z}) {
    EXPECT_NEAR(moment, polyMoment, 1e-6 * polyMoment);
    EXPECT_NEAR(moment, idealMoment, 0.02 * idealMoment);
  }
  std::printf("sampled icosphere: %zu particles, moment %+.3f%% against the ideal sphere\n",
              sampled.centres.size(), 100 * (sampled.shape.principalInertia.x / idealMoment - 1.0));
}

TEST(MassProperties, CylinderIsTheInscribedPrismWoundOutward) {
  // A prism on a regular n-gon inscribed in a circle of radius r: area n r² sin(2π/n) / 2; its
  // polar moment about the axis per unit mass r² (2 + cos(2π/n)) / 6 (the n triangles from the
  // centre); the moment about a transverse axis through the centre adds h²/12.
  const double r = 0.05, h = 0.02, density = 1000.0;
  const int n = 24;
  const Vec3 centre{0.1f, -0.2f, 0.3f};
  const TriangleMesh cylinder = cylinderMesh(r, h, n, centre);
  EXPECT_EQ(cylinder.triangles.size(), 4u * n);
  const SolidProperties solid = solidProperties(cylinder, density);
  // The vertices are floats: the solid is the prism to about 1e-7 of each length.
  const double tolerance = 1e-5;
  EXPECT_FALSE(solid.woundInward);
  const double area = 0.5 * n * r * r * std::sin(2.0 * std::numbers::pi / n);
  EXPECT_NEAR(solid.volume, area * h, tolerance * area * h);
  EXPECT_LT((toVector(solid.massProperties.centreOfMass) - toEigen(centre)).norm(), 1e-7);
  const double mass = density * area * h;
  const double polar = r * r * (2.0 + std::cos(2.0 * std::numbers::pi / n)) / 6.0;
  const Eigen::Matrix3d inertia = toMatrix(solid.massProperties.inertia);
  EXPECT_NEAR(inertia(1, 1), mass * polar, tolerance * mass * polar);
  EXPECT_NEAR(inertia(0, 0), mass * (0.5 * polar + h * h / 12.0), tolerance * mass * polar);
  EXPECT_NEAR(inertia(2, 2), inertia(0, 0), tolerance * mass * polar);
  EXPECT_TRUE(sampleMesh(cylinder, 0.01f).closed);
  EXPECT_THROW(cylinderMesh(r, h, 2), InvalidArgument);
  EXPECT_THROW(cylinderMesh(-r, h, n), InvalidArgument);
}

TEST(MassProperties, InwardWindingIsTheSameSolid) {
  TriangleMesh box = boxMesh({0, 0, 0}, {0.2f, 0.1f, 0.1f});
  for (auto& tri : box.triangles) std::swap(tri[1], tri[2]);
  const SolidProperties solid = solidProperties(box, 1000.0);
  EXPECT_TRUE(solid.woundInward);
  EXPECT_NEAR(solid.volume, 0.002, 1e-9);
  EXPECT_NEAR(solid.massProperties.inertia[0][0], 2.0 / 12.0 * (0.01 + 0.01), 1e-8);
  const SampledMesh sampled = sampleMesh(box, 0.02f);
  ASSERT_EQ(sampled.warnings.size(), 1u);
  EXPECT_NE(sampled.warnings[0].find("wound inward"), std::string::npos) << sampled.warnings[0];
  EXPECT_TRUE(sampled.closed);
}

TEST(MassProperties, TwoCubesSharingAnEdgeAreOneClosedSolid) {
  // Four triangles meet at the shared edge, two in each direction: still a closed surface.
  TriangleMesh a = namedBox({0, 0, 0}, {1, 1, 1}, "two cubes");
  const TriangleMesh b = boxMesh({1, 1, 0}, {2, 2, 1});
  const auto offset = std::uint32_t(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto tri : b.triangles)
    a.triangles.push_back({tri[0] + offset, tri[1] + offset, tri[2] + offset});
  const MeshEdges edges = analyseEdges(a);
  EXPECT_TRUE(edges.closed());
  EXPECT_EQ(edges.edges, 2u * 18u - 1u);
  const SolidProperties solid = solidProperties(a, 1.0);
  EXPECT_NEAR(solid.volume, 2.0, 1e-12);
  EXPECT_LT((toVector(solid.massProperties.centreOfMass) - Eigen::Vector3d(1, 1, 0.5)).norm(),
            1e-12);
}

TEST(MassProperties, SampledBoxBodyTakesTheSolidsMassNotTheSpheres) {
  const Vec3 lo{0.5f, 0.0f, -0.2f}, hi{0.9f, 0.3f, 0.0f};
  const Eigen::Vector3d size = toEigen(hi) - toEigen(lo);
  const float density = 1500.0f, diameter = 0.02f;
  const SampledMesh sampled = sampleMesh(boxMesh(lo, hi), diameter, {.density = density});
  EXPECT_TRUE(sampled.closed);
  EXPECT_TRUE(sampled.warnings.empty());
  const double mass = density * size.prod();
  EXPECT_NEAR(sampled.volume, size.prod(), 1e-9);
  EXPECT_NEAR(sampled.surfaceArea,
              2.0 * (size.x() * size.y() + size.y() * size.z() + size.x() * size.z()), 1e-9);
  EXPECT_NEAR(sampled.shape.mass, mass, 1e-6 * mass);
  EXPECT_NEAR(sampled.massProperties.mass, mass, 1e-9 * mass);

  // Principal moments (ascending) of the solid box, not of the shell of spheres.
  Eigen::Vector3d moments = boxInertia(mass, size).diagonal();
  std::sort(moments.data(), moments.data() + 3);
  const Vec3 principal = sampled.shape.principalInertia;
  const double error = (Eigen::Vector3d(principal.x, principal.y, principal.z) - moments)
                           .cwiseQuotient(moments)
                           .cwiseAbs()
                           .maxCoeff();
  std::printf("sampled box: principal moments within %.3g of the solid's\n", error);
  EXPECT_LT(error, 1e-6);
  const ParticleTemplate shell = makeParticleTemplate(sampled.centres, diameter, density);
  EXPECT_GT(std::abs(shell.mass / sampled.shape.mass - 1.0), 0.2);  // a shell weighs otherwise

  // Offsets are the centres about the box's centre of mass, in the principal frame.
  const Eigen::Vector3d centre = 0.5 * (toEigen(lo) + toEigen(hi));
  EXPECT_LT((toVector(sampled.massProperties.centreOfMass) - centre).norm(), 1e-9);
  const Quat& q = sampled.shape.principalRotation;
  const Eigen::Matrix3d axes = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
  for (std::size_t i = 0; i < sampled.centres.size(); ++i) {
    const Eigen::Vector3d back = axes * toEigen(sampled.shape.offsets[i]) + centre;
    ASSERT_LT((back - toEigen(sampled.centres[i])).norm(), 1e-6) << "particle " << i;
  }
}

TEST(MassProperties, GivenMassScalesTheSolid) {
  const SampledMesh sampled =
      sampleMesh(icosphereMesh(0.1, 3), 0.02f, {.density = 1.0f, .mass = 5.0f});
  EXPECT_FLOAT_EQ(sampled.shape.mass, 5.0f);
  const double moment = 0.4 * 5.0 * 0.1 * 0.1;
  EXPECT_NEAR(sampled.shape.principalInertia.x, moment, 0.02 * moment);
  EXPECT_NEAR(sampled.massProperties.inertia[1][1], moment, 0.02 * moment);
}

TEST(MassProperties, OpenMeshWarnsAndFallsBackToItsParticles) {
  TriangleMesh box = namedBox({0, 0, 0}, {0.2f, 0.1f, 0.1f}, "box without a lid");
  box.triangles.resize(10);  // the two triangles of the +z face are gone
  const MeshEdges edges = analyseEdges(box);
  EXPECT_FALSE(edges.closed());
  EXPECT_EQ(edges.openEdges, 4u);
  EXPECT_EQ(edges.misorientedEdges, 0u);
  EXPECT_THROW(solidProperties(box, 1000.0), MeshError);

  const float diameter = 0.02f, density = 2000.0f;
  ::testing::internal::CaptureStderr();
  const SampledMesh sampled = sampleMesh(box, diameter, {.density = density});
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(sampled.closed);
  EXPECT_EQ(sampled.volume, 0.0);
  ASSERT_EQ(sampled.warnings.size(), 1u);
  EXPECT_NE(sampled.warnings[0].find("'box without a lid': not closed (4 open"), std::string::npos)
      << sampled.warnings[0];
  EXPECT_NE(printed.find(sampled.warnings[0]), std::string::npos) << printed;
  // The documented fallback: the particles as solid spheres, each of density · πd³/6.
  const double sphere = density * std::numbers::pi * diameter * diameter * diameter / 6.0;
  EXPECT_NEAR(sampled.shape.mass, double(sampled.centres.size()) * sphere,
              1e-6 * sampled.shape.mass);
  const ParticleTemplate particles = makeParticleTemplate(sampled.centres, diameter, density);
  EXPECT_FLOAT_EQ(sampled.shape.principalInertia.x, particles.principalInertia.x);
  EXPECT_FLOAT_EQ(sampled.shape.principalInertia.z, particles.principalInertia.z);

  // ... or scaled to a given mass.
  const SampledMesh heavy = sampleMesh(box, diameter, {.mass = 3.0f});
  EXPECT_FLOAT_EQ(heavy.shape.mass, 3.0f);
  EXPECT_NE(heavy.warnings.at(0).find("scaled to MeshSampling.mass = 3 kg"), std::string::npos);

  try {
    sampleMesh(box, diameter, {.fillVolume = true});
    FAIL() << "filling an open mesh went through";
  } catch (const MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'box without a lid'"), std::string::npos) << message;
    EXPECT_NE(message.find("fillVolume needs a closed mesh"), std::string::npos) << message;
  }
}

TEST(MassProperties, OneFlippedTriangleMakesMisorientedEdges) {
  TriangleMesh box = namedBox({0, 0, 0}, {0.1f, 0.1f, 0.1f}, "box with a flipped triangle");
  std::swap(box.triangles[3][1], box.triangles[3][2]);
  const MeshEdges edges = analyseEdges(box);
  EXPECT_EQ(edges.edges, 18u);
  EXPECT_EQ(edges.openEdges, 0u);
  EXPECT_EQ(edges.misorientedEdges, 3u);
  EXPECT_FALSE(edges.closed());
  const SampledMesh sampled = sampleMesh(box, 0.02f);
  EXPECT_FALSE(sampled.closed);
  EXPECT_NE(sampled.warnings.at(0).find("3 misoriented"), std::string::npos);
}

TEST(MassProperties, ClosedSurfaceWithoutVolumeIsRefused) {
  // A square and the same square wound the other way: every edge pairs up, nothing is inside.
  TriangleMesh sheet;
  sheet.source = "doubled sheet";
  sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}};
  EXPECT_TRUE(analyseEdges(sheet).closed());
  try {
    solidProperties(sheet, 1000.0);
    FAIL() << "a flat closed surface gave a solid";
  } catch (const MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'doubled sheet'"), std::string::npos) << message;
    EXPECT_NE(message.find("encloses no volume"), std::string::npos) << message;
  }
  EXPECT_THROW(sampleMesh(sheet, 0.02f), MeshError);
}

TEST(MassProperties, RepeatedCornersPerFaceStillCountAsClosed) {
  // Every triangle with corners of its own, as STL files store them.
  const TriangleMesh shared = boxMesh({0, 0, 0}, {0.1f, 0.2f, 0.3f});
  TriangleMesh separate;
  separate.source = "triangle soup";
  for (const auto& tri : shared.triangles) {
    const auto base = std::uint32_t(separate.vertices.size());
    for (std::uint32_t i : tri) separate.vertices.push_back(shared.vertices[i]);
    separate.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(analyseEdges(separate).closed());
  EXPECT_NEAR(solidProperties(separate, 1.0).volume, 0.006, 1e-9);
  EXPECT_EQ(sampleMesh(separate, 0.02f).centres.size(), sampleMesh(shared, 0.02f).centres.size());
}

}  // namespace
}  // namespace sandphys
