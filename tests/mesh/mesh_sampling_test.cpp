// sampleMesh's surface and volume sampling: the spacing rule, welding, determinism, filling.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "mesh/mesh_shapes.h"

namespace sandphys {
namespace {

using mesh_testing::namedBox;
using mesh_testing::namedIcosphere;
using mesh_testing::toEigen;

constexpr float kDiameter = 0.02f;
constexpr double kSpacing = kDefaultMeshSpacing * kDiameter;  // h

// The covering rule of MeshSampling::spacing: no point of the surface is farther than h/√3 from
// a sample; the tolerance is float rounding of the centres. With `tight`, the largest gap must
// also come near the rule: a sampler twice as fine as needed (gaps of h/(2√3)) fails.
void expectCoveredWithinRule(const TriangleMesh& mesh, const SampledMesh& sampled, double spacing,
                             bool tight) {
  const double rule = spacing / std::numbers::sqrt3;
  double worst = 0.0;
  for (const Eigen::Vector3d& p : mesh_testing::randomSurfacePoints(mesh, 3000, 11)) {
    worst = std::max(worst, mesh_testing::nearestDistance(sampled.centres, p));
  }
  std::printf("%s: %zu samples, largest gap %.6g m = %.4f h (rule: h/sqrt(3) = %.4f h)\n",
              mesh.source.c_str(), sampled.centres.size(), worst, worst / spacing,
              1.0 / std::numbers::sqrt3);
  EXPECT_LE(worst, rule + 1e-6) << mesh.source;
  if (tight) {
    EXPECT_GT(worst, 0.7 * rule) << mesh.source;
  }
}

// Neighbouring samples are at most h apart (< d), and welding left no duplicates.
void expectNeighboursWithinSpacing(const SampledMesh& sampled, double spacing, float diameter) {
  const std::vector<double> nearest = mesh_testing::nearestNeighbourDistances(sampled.centres);
  const double largest = *std::max_element(nearest.begin(), nearest.end());
  const double smallest = *std::min_element(nearest.begin(), nearest.end());
  std::printf("nearest neighbour: largest %.4f d, smallest %.4f d\n", largest / diameter,
              smallest / diameter);
  EXPECT_LE(largest, spacing + 1e-6);
  EXPECT_LT(largest, diameter);
  EXPECT_GT(smallest, 1e-3 * spacing);
}

TEST(MeshSampling, BoxSurfaceIsCoveredWithinTheSpacingRule) {
  // Faces of three sizes: neighbouring triangles are cut into different numbers of parts.
  const TriangleMesh box =
      namedBox({-0.15f, 0.0f, -0.05f}, {0.15f, 0.2f, 0.05f}, "box 30x20x10 cm");
  const SampledMesh sampled = sampleMesh(box, kDiameter);
  expectCoveredWithinRule(box, sampled, kSpacing, true);
  expectNeighboursWithinSpacing(sampled, kSpacing, kDiameter);
}

TEST(MeshSampling, SphereSurfaceIsCoveredWithinTheSpacingRule) {
  // Triangles of about 1.5 h: each is cut in two, so the lattice changes at every edge.
  const TriangleMesh sphere = namedIcosphere(0.1, 3, {0.5f, 1.0f, -0.25f}, "icosphere r 10 cm");
  const SampledMesh sampled = sampleMesh(sphere, kDiameter);
  expectCoveredWithinRule(sphere, sampled, kSpacing, true);
  expectNeighboursWithinSpacing(sampled, kSpacing, kDiameter);
}

TEST(MeshSampling, AMeshFinerThanTheSpacingGetsTheParticlesTheSpacingAsksFor) {
  // A 14 cm sphere of 81,920 triangles (edges about 1.2 mm, a fourteenth of h): one particle per
  // vertex would be 40,962. The spacing asks for about 1.15 · area / h² on a lattice; thinning
  // a far finer mesh greedily, in mesh order, leaves samples about 0.56 h apart at random, some
  // 2.3 times the lattice's count (630 against 278).
  const TriangleMesh sphere = namedIcosphere(0.07, 6, {}, "dense icosphere");
  ASSERT_EQ(sphere.triangles.size(), 81920u);
  const SampledMesh sampled = sampleMesh(sphere, kDiameter);
  const double lattice = 2.0 / std::numbers::sqrt3 * sampled.surfaceArea / (kSpacing * kSpacing);
  std::printf("dense icosphere: %zu particles, %.0f on a lattice of the spacing\n",
              sampled.centres.size(), lattice);
  EXPECT_LT(double(sampled.centres.size()), 2.5 * lattice);
  EXPECT_GT(double(sampled.centres.size()), 0.8 * lattice);
  expectCoveredWithinRule(sphere, sampled, kSpacing, true);
}

TEST(MeshSampling, CoarserSpacingStillKeepsItsRule) {
  const TriangleMesh sphere = namedIcosphere(0.1, 2, {}, "icosphere r 10 cm, coarse");
  const double spacing = 1.5 * kDiameter;
  const SampledMesh sampled = sampleMesh(sphere, kDiameter, {.spacing = float(spacing)});
  expectCoveredWithinRule(sphere, sampled, spacing, false);
}

TEST(MeshSampling, CubeCornersAndEdgesAreWeldedIntoOneLattice) {
  // Each face is a square of two triangles cut n times: (n + 1)² points per face, and the cube
  // shares its edges and corners, so 6 (n + 1)² - 12 (n + 1) + 8 = 6 n² + 2 particles in all.
  const float side = 0.1f;
  const TriangleMesh cube = boxMesh({0.3f, -0.2f, 0.1f}, {0.3f + side, -0.2f + side, 0.1f + side});
  const SampledMesh sampled = sampleMesh(cube, kDiameter);
  const double n = std::ceil(side * std::numbers::sqrt2 / kSpacing);
  EXPECT_EQ(sampled.centres.size(), std::size_t(6 * n * n + 2));
  EXPECT_EQ(sampled.surfaceParticles, sampled.centres.size());
  EXPECT_EQ(sampled.shape.offsets.size(), sampled.centres.size());
}

TEST(MeshSampling, SameMeshGivesTheSameParticlesInTheSameOrder) {
  const TriangleMesh sphere = icosphereMesh(0.08, 3, {0.1f, 0.2f, 0.3f});
  const SampledMesh first = sampleMesh(sphere, kDiameter, {.fillVolume = true});
  const SampledMesh second = sampleMesh(sphere, kDiameter, {.fillVolume = true});
  ASSERT_EQ(first.centres.size(), second.centres.size());
  for (std::size_t i = 0; i < first.centres.size(); ++i) {
    EXPECT_EQ(first.centres[i].x, second.centres[i].x);
    EXPECT_EQ(first.centres[i].y, second.centres[i].y);
    EXPECT_EQ(first.centres[i].z, second.centres[i].z);
    EXPECT_EQ(first.shape.offsets[i].x, second.shape.offsets[i].x);
  }
}

// The interior of a box, computed independently: the lattice of spacing h centred on the box,
// points inside it and at least h/2 from every surface sample, ordered by z, then y, then x.
std::vector<Eigen::Vector3d> expectedBoxInterior(Eigen::Vector3d lo, Eigen::Vector3d hi,
                                                 const std::vector<Vec3>& surface) {
  int count[3];
  Eigen::Vector3d start;
  for (int a = 0; a < 3; ++a) {
    count[a] = int(std::floor((hi(a) - lo(a)) / kSpacing)) + 1;
    start(a) = 0.5 * (lo(a) + hi(a)) - 0.5 * (count[a] - 1) * kSpacing;
  }
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < count[2]; ++k) {
    for (int j = 0; j < count[1]; ++j) {
      for (int i = 0; i < count[0]; ++i) {
        const Eigen::Vector3d p = start + kSpacing * Eigen::Vector3d(i, j, k);
        if ((p.array() <= lo.array()).any() || (p.array() >= hi.array()).any()) continue;
        if (mesh_testing::nearestDistance(surface, p) < 0.5 * kSpacing) continue;
        out.push_back(p);
      }
    }
  }
  return out;
}

TEST(MeshSampling, FilledBoxHasEveryInteriorLatticePoint) {
  // 0.3 / h = 18.75: the lattice stays clear of the faces, but its rows with y = z run exactly
  // along the diagonals of the x faces, where two triangles meet (each must count once).
  const Vec3 lo{-0.15f, -0.15f, -0.15f}, hi{0.15f, 0.15f, 0.15f};
  const TriangleMesh box = namedBox(lo, hi, "filled box");
  const SampledMesh sampled = sampleMesh(box, kDiameter, {.fillVolume = true});
  const std::vector<Vec3> surface(sampled.centres.begin(),
                                  sampled.centres.begin() + long(sampled.surfaceParticles));
  const std::vector<Eigen::Vector3d> expected =
      expectedBoxInterior(toEigen(lo), toEigen(hi), surface);
  ASSERT_EQ(sampled.centres.size() - sampled.surfaceParticles, expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_LT((toEigen(sampled.centres[sampled.surfaceParticles + i]) - expected[i]).norm(), 1e-6)
        << "interior point " << i;
  }
  std::printf("filled box: %zu surface + %zu interior particles\n", sampled.surfaceParticles,
              expected.size());
}

TEST(MeshSampling, FilledSphereHoldsItsInteriorAndNothingOutside) {
  const Vec3 centre{0.05f, -0.02f, 0.01f};
  const double radius = 0.1;
  const TriangleMesh sphere = namedIcosphere(radius, 3, centre, "filled icosphere");
  const SampledMesh sampled = sampleMesh(sphere, kDiameter, {.fillVolume = true});
  // The polyhedron lies between its inradius and the sphere.
  double inradius = radius;
  for (const auto& tri : sphere.triangles) {
    const Eigen::Vector3d a = toEigen(sphere.vertices[tri[0]]) - toEigen(centre);
    const Eigen::Vector3d b = toEigen(sphere.vertices[tri[1]]) - toEigen(centre);
    const Eigen::Vector3d c = toEigen(sphere.vertices[tri[2]]) - toEigen(centre);
    inradius = std::min(inradius, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  const std::vector<Vec3> surface(sampled.centres.begin(),
                                  sampled.centres.begin() + long(sampled.surfaceParticles));
  std::vector<Eigen::Vector3d> interior;
  for (std::size_t i = sampled.surfaceParticles; i < sampled.centres.size(); ++i) {
    interior.push_back(toEigen(sampled.centres[i]));
    EXPECT_LT((interior.back() - toEigen(centre)).norm(), radius) << "interior point " << i;
    EXPECT_GE(mesh_testing::nearestDistance(surface, interior.back()), 0.5 * kSpacing - 1e-6);
  }
  // Every lattice point well inside must be there: the lattice is centred on the bounding box.
  Eigen::Vector3d lo = toEigen(sphere.vertices[0]), hi = lo;
  for (const Vec3& v : sphere.vertices) {
    lo = lo.cwiseMin(toEigen(v));
    hi = hi.cwiseMax(toEigen(v));
  }
  int count[3];
  Eigen::Vector3d start;
  for (int a = 0; a < 3; ++a) {
    count[a] = int(std::floor((hi(a) - lo(a)) / kSpacing)) + 1;
    start(a) = 0.5 * (lo(a) + hi(a)) - 0.5 * (count[a] - 1) * kSpacing;
  }
  std::size_t required = 0;
  for (int k = 0; k < count[2]; ++k) {
    for (int j = 0; j < count[1]; ++j) {
      for (int i = 0; i < count[0]; ++i) {
        const Eigen::Vector3d p = start + kSpacing * Eigen::Vector3d(i, j, k);
        if ((p - toEigen(centre)).norm() >= inradius - 1e-6) continue;
        if (mesh_testing::nearestDistance(surface, p) < 0.5 * kSpacing + 1e-6) continue;
        ++required;
        const bool found = std::any_of(interior.begin(), interior.end(),
                                       [&](const auto& q) { return (q - p).norm() < 1e-6; });
        EXPECT_TRUE(found) << "lattice point (" << p.transpose() << ") is missing";
      }
    }
  }
  EXPECT_GT(required, 100u);
  std::printf("filled sphere: %zu surface + %zu interior particles (%zu checked)\n",
              sampled.surfaceParticles, interior.size(), required);
}

TEST(MeshSampling, ParticleLimitIsEnforcedAndNamed) {
  const TriangleMesh box = namedBox({0, 0, 0}, {1, 1, 1}, "big box");
  try {
    sampleMesh(box, 0.002f);  // 12 triangles cut 884 times: about 12 · 884² / 2 = 4.7 million
    FAIL() << "sampling a 1 m box at d = 2 mm went through";
  } catch (const CapacityExceeded& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'big box'"), std::string::npos) << message;
    EXPECT_NE(message.find("MeshSampling.maxParticles = 1048576"), std::string::npos) << message;
  }
  // The surface fits but the filling does not: the count is checked as the particles come.
  const TriangleMesh cube = namedBox({0, 0, 0}, {0.2f, 0.2f, 0.2f}, "filled cube");
  const std::size_t surface = sampleMesh(cube, kDiameter).centres.size();
  try {
    sampleMesh(cube, kDiameter, {.fillVolume = true, .maxParticles = std::uint32_t(surface + 10)});
    FAIL() << "filling went past MeshSampling.maxParticles";
  } catch (const CapacityExceeded& e) {
    EXPECT_NE(
        std::string(e.what()).find("MeshSampling.maxParticles = " + std::to_string(surface + 10)),
        std::string::npos)
        << e.what();
  }
}

TEST(MeshSampling, ABodyOfManyParticlesIsWarnedAboutWithItsCount) {
  // A 1 m cube at d = 2 cm: its faces cut into right triangles with hypotenuses <= h give
  // 47,528 particles.
  const SampledMesh big = sampleMesh(namedBox({0, 0, 0}, {1, 1, 1}, "metre cube"), kDiameter);
  ASSERT_GT(big.centres.size(), kLargeBodyWarningParticles);
  ASSERT_FALSE(big.warnings.empty());
  EXPECT_NE(big.warnings.back().find(std::to_string(big.centres.size()) + " particles"),
            std::string::npos)
      << big.warnings.back();
  const SampledMesh small = sampleMesh(namedBox({0, 0, 0}, {0.1f, 0.1f, 0.1f}, "cube"), kDiameter);
  EXPECT_TRUE(small.warnings.empty());
}

TEST(MeshSampling, BadOptionsAreRefused) {
  const TriangleMesh cube = boxMesh({0, 0, 0}, {0.1f, 0.1f, 0.1f});
  EXPECT_THROW(sampleMesh(cube, 0.0f), InvalidArgument);
  EXPECT_THROW(sampleMesh(cube, std::nanf("")), InvalidArgument);
  EXPECT_THROW(sampleMesh(cube, kDiameter, {.spacing = -0.01f}), InvalidArgument);
  EXPECT_THROW(sampleMesh(cube, kDiameter, {.density = 0.0f}), InvalidArgument);
  EXPECT_THROW(sampleMesh(cube, kDiameter, {.mass = -1.0f}), InvalidArgument);
  EXPECT_THROW(sampleMesh(cube, kDiameter, {.maxParticles = 0}), InvalidArgument);
  try {
    sampleMesh(cube, kDiameter, {.spacing = 1.8f * kDiameter});
    FAIL() << "a spacing above sqrt(3) d went through";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("MeshSampling.spacing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sandphys
