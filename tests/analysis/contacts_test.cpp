// The contact-network tools against data with known answers.
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

TEST(ForceCorrelation, TwoBlobsOfDifferentForcesGiveTheExactRatios) {
  // Blob A (forces 3) and blob B (forces 1), 1 m apart, each 0.05 m across: within a blob
  // ⟨f f⟩ = (9 + 1) / 2 = 5 over ⟨f⟩² = 4, across them 3 / 4.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> offset(-0.025, 0.025);
  std::vector<Vec3> points;
  std::vector<double> forces;
  for (int blob = 0; blob < 2; ++blob) {
    for (int i = 0; i < 40; ++i) {
      points.push_back(
          {float(blob + offset(random)), float(offset(random)), float(offset(random))});
      forces.push_back(blob == 0 ? 3.0 : 1.0);
    }
  }
  const ForceCorrelation g = forceCorrelation(points, forces, 0.1, 1.2);
  ASSERT_EQ(g.distance.size(), 12u);
  EXPECT_NEAR(g.correlation[0], 1.25, 1e-12);
  EXPECT_EQ(g.pairs[0], 2u * 40 * 39 / 2);
  std::size_t across = 0;
  for (std::size_t k = 9; k < 12; ++k) {
    if (g.pairs[k] == 0) continue;
    EXPECT_NEAR(g.correlation[k], 0.75, 1e-12);
    across += g.pairs[k];
  }
  EXPECT_EQ(across, 40u * 40);
}

TEST(ForceCorrelation, IndependentForcesAreUncorrelatedAtEveryDistance) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::exponential_distribution<double> force(1.0);
  std::vector<Vec3> points;
  std::vector<double> forces;
  for (int i = 0; i < 3000; ++i) {
    points.push_back({float(unit(random)), float(unit(random)), float(unit(random))});
    forces.push_back(force(random));
  }
  const ForceCorrelation g = forceCorrelation(points, forces, 0.05, 0.5);
  for (std::size_t k = 1; k < g.distance.size(); ++k) {
    EXPECT_NEAR(g.correlation[k], 1.0, 0.06) << "at " << g.distance[k] << " m";
  }
  EXPECT_NE(errorOf([&] { forceCorrelation(points, forces, 0.0, 0.5); }).find("binWidth"),
            std::string::npos);
  forces.pop_back();
  EXPECT_NE(errorOf([&] {
              forceCorrelation(points, forces, 0.05, 0.5);
            }).find("3000 points but 2999 forces"),
            std::string::npos);
}

TEST(ContactAngles, RandomDirectionsFollowTheCosineAndFlatOnesFillTheFirstBin) {
  std::mt19937 random(9);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vec3> normals;
  for (int i = 0; i < 200000; ++i) {
    normals.push_back({float(normal(random)), float(normal(random)), float(normal(random))});
  }
  const AngleDistribution angles = contactAngles(normals, 9);
  double integral = 0.0;
  for (std::size_t k = 0; k < angles.density.size(); ++k) {
    EXPECT_NEAR(angles.density[k], angles.isotropic[k], 0.03 * angles.isotropic[0]);
    integral += angles.density[k] * 10.0;
  }
  EXPECT_NEAR(integral, 1.0, 1e-9);
  const std::vector<Vec3> flat{{1, 0, 0}, {0, 0, -2}, {0.5f, 0, 0.5f}};
  const AngleDistribution sideways = contactAngles(flat, 9);
  EXPECT_NEAR(sideways.density[0], 0.1, 1e-12);
  EXPECT_NE(errorOf([] {
              contactAngles(std::vector<Vec3>{{0, 0, 0}});
            }).find("normals[0] is zero"),
            std::string::npos);
}

TEST(NetworkFractions, ExponentialForcesSplitAsTheClosedForm) {
  // For f ~ Exp(1): P(f > c) = e^-c and the force carried above c is (1 + c) e^-c.
  std::mt19937 random(13);
  std::exponential_distribution<double> force(1.0);
  std::vector<double> forces;
  for (int i = 0; i < 200000; ++i) forces.push_back(force(random));
  const NetworkFractions split = networkFractions(forces, 0.5, 3.0);
  ASSERT_EQ(split.threshold.size(), 7u);
  for (std::size_t k = 0; k < split.threshold.size(); ++k) {
    const double c = split.threshold[k];
    EXPECT_NEAR(split.contacts[k], std::exp(-c), 0.01) << "f_cut " << c;
    EXPECT_NEAR(split.force[k], (1.0 + c) * std::exp(-c), 0.01) << "f_cut " << c;
  }
  const NetworkFractions equal = networkFractions(std::vector<double>{2, 2, 2}, 1.0, 1.0);
  EXPECT_EQ(equal.contacts, (std::vector<double>{1.0, 0.0}));
}

}  // namespace
}  // namespace sandphys::analysis
