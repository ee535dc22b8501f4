// The angle of repose from granule centres: synthetic heaps of known slope give it back, and bad
// input gets its error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <sandphys/analysis.h>
#include <sandphys/error.h>

#include "error_of.h"

namespace sandphys::analysis {
namespace {

using testing::errorOf;

constexpr double kDegree = std::numbers::pi / 180.0;

// A cone of `degrees` and base radius `base` (m) standing on a floor at y = floorY around the
// axis (ax, az), filled with centres on a jittered lattice of `spacing` (so that, as in a real
// heap, the top centre of every column lies within a spacing of the surface however tall the
// column is); the surface is roughened by half a spacing either way.
std::vector<Vec3> coneHeap(double degrees, double base, double spacing, double floorY, double ax,
                           double az, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * spacing, 0.3 * spacing);
  std::uniform_real_distribution<double> rough(-0.5 * spacing, 0.5 * spacing);
  const double slope = std::tan(degrees * kDegree);
  const auto across = static_cast<int>(base / spacing);
  const auto up = static_cast<int>(base * slope / spacing) + 1;
  std::vector<Vec3> centres;
  for (int i = -across; i <= across; ++i) {
    for (int k = -across; k <= across; ++k) {
      for (int j = 0; j <= up; ++j) {
        const double x = i * spacing + jitter(random);
        const double z = k * spacing + jitter(random);
        const double y = j * spacing + 0.5 * spacing + jitter(random);
        const double r = std::hypot(x, z);
        if (r > base || y > (base - r) * slope + rough(random)) continue;
        centres.push_back({float(ax + x), float(floorY + y), float(az + z)});
      }
    }
  }
  return centres;
}

TEST(AngleOfRepose, ConesOfKnownSlopeGiveTheirAngleBack) {
  for (const double degrees : {12.0, 22.0, 30.0}) {
    const double d = 0.02;
    std::vector<Vec3> centres = coneHeap(degrees, 30 * d, d, 0.1, 0.3, -0.2, 7);
    const HeapAngle heap =
        angleOfRepose(centres, {.axisX = 0.3, .axisZ = -0.2, .floorY = 0.1, .binWidth = d});
    EXPECT_NEAR(heap.degrees, degrees, 1.0) << "cone of " << degrees << " degrees";
    EXPECT_NEAR(heap.peakHeight, 30 * d * std::tan(degrees * kDegree), 1.0 * d);
    EXPECT_GT(heap.radius.size(), 100u);
    EXPECT_EQ(heap.radius.size(), heap.height.size());
  }
}

// A ridge along z leaning on a wall at x = wallX (the sump of the paper's Fig. 15): a wedge of
// `degrees` falling in +x from height `top` at the wall, `depth` long in z, on the same jittered
// lattice and rough surface as coneHeap.
std::vector<Vec3> ridgeHeap(double degrees, double top, double depth, double spacing, double wallX,
                            unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * spacing, 0.3 * spacing);
  std::uniform_real_distribution<double> rough(-0.5 * spacing, 0.5 * spacing);
  const double slope = std::tan(degrees * kDegree);
  const auto across = static_cast<int>(top / slope / spacing) + 1;
  const auto along = static_cast<int>(depth / spacing);
  const auto up = static_cast<int>(top / spacing) + 1;
  std::vector<Vec3> centres;
  for (int i = 0; i <= across; ++i) {
    for (int k = 0; k < along; ++k) {
      for (int j = 0; j <= up; ++j) {
        const double x = (i + 0.5) * spacing + jitter(random);
        const double y = (j + 0.5) * spacing + jitter(random);
        if (y > top - x * slope + rough(random)) continue;
        centres.push_back({float(wallX + x), float(y), float(k * spacing + jitter(random))});
      }
    }
  }
  return centres;
}

TEST(AngleOfRepose, RidgesOfKnownSlopeGiveTheirAngleBack) {
  for (const double degrees : {15.0, 30.0}) {
    const double d = 0.02;
    const std::vector<Vec3> centres = ridgeHeap(degrees, 12 * d, 16 * d, d, -0.1, 5);
    const HeapAngle heap =
        angleOfRepose(centres, {.shape = HeapShape::ridge, .axisX = -0.1, .binWidth = d});
    EXPECT_NEAR(heap.degrees, degrees, 1.0) << "ridge of " << degrees << " degrees";
    EXPECT_NEAR(heap.peakHeight, 12 * d, 1.0 * d);
    // Read as a cone around the wall's foot, the same ridge's distances are wrong: the check can
    // tell the shapes apart.
    const HeapAngle asCone = angleOfRepose(centres, {.axisX = -0.1, .axisZ = 0.0, .binWidth = d});
    EXPECT_GT(std::abs(asCone.degrees - degrees), 2.0) << "ridge of " << degrees << " degrees";
  }
}

TEST(AngleOfRepose, GrainsRestingOnTheFlankAndRolledOffTheFloorDoNotTiltIt) {
  const double d = 0.02;
  std::vector<Vec3> centres = coneHeap(25.0, 30 * d, d, 0.0, 0.0, 0.0, 11);
  const HeapAngle clean = angleOfRepose(centres, {.binWidth = d, .maxRadius = 32 * d});
  // Loose grains sitting 3 d proud of the flank in one sector, and grains that fell off the
  // floor's edge, far below and far out.
  for (int i = 0; i < 12; ++i) {
    const double r = (8 + i) * d;
    centres.push_back({float(r), float((30 * d - r) * std::tan(25.0 * kDegree) + 3 * d), 0.0f});
    centres.push_back({float(40 * d + i * d), -0.5f, 0.0f});
  }
  const HeapAngle heap = angleOfRepose(centres, {.binWidth = d, .maxRadius = 32 * d});
  EXPECT_NEAR(heap.degrees, 25.0, 1.0);
  EXPECT_NEAR(heap.degrees, clean.degrees, 0.5);
  int rejected = 0;
  for (double w : heap.fit.weights) rejected += w == 0.0 ? 1 : 0;
  EXPECT_GT(rejected, 0) << "the proud grains are outliers";
}

TEST(AngleOfRepose, BadInputNamesTheProblem) {
  const std::vector<Vec3> heap = coneHeap(20.0, 0.6, 0.02, 0.0, 0.0, 0.0, 3);
  EXPECT_NE(errorOf([&] { angleOfRepose(heap, {.binWidth = 0.0}); }).find("options.binWidth is 0"),
            std::string::npos);
  EXPECT_NE(
      errorOf([&] { angleOfRepose(heap, {.maxRadius = -1.0}); }).find("options.maxRadius is -1"),
      std::string::npos);
  EXPECT_NE(errorOf([&] {
              angleOfRepose(heap, {.flankFrom = 0.9, .flankTo = 0.5});
            }).find("must satisfy 0 <= flankFrom < flankTo <= 1"),
            std::string::npos);
  std::vector<Vec3> broken = heap;
  broken[5].y = std::nanf("");
  EXPECT_NE(errorOf([&] { angleOfRepose(broken, {}); }).find("centres[5]"), std::string::npos);
  // Three grains are no heap: too few surface cells on any flank.
  const std::vector<Vec3> tiny{{0, 0.01f, 0}, {0.02f, 0.0f, 0}, {0, 0.0f, 0.02f}};
  EXPECT_NE(errorOf([&] { angleOfRepose(tiny, {}); }).find("at least 3 needed"), std::string::npos);
}

}  // namespace
}  // namespace sandphys::analysis
