// Curve fits against data with known answers: exact data gives back its parameters to rounding,
// noisy data within its noise, and every bad input its error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <sandphys/analysis.h>
#include <sandphys/error.h>

#include "error_of.h"

namespace sandphys::analysis {
namespace {

using testing::errorOf;

TEST(LineFit, ExactLineFarFromTheOriginComesBackToRounding) {
  // Times in seconds late in a long run: a raw-moment formula would lose the slope here.
  std::vector<double> x;
  std::vector<double> y;
  for (int i = 0; i < 50; ++i) {
    x.push_back(1.0e6 + 0.01 * i);
    y.push_back(-250.0 * x.back() + 3.0e8);
  }
  const LineFit fit = fitLine(x, y);
  EXPECT_NEAR(fit.slope, -250.0, 1e-6);
  EXPECT_NEAR(fit.intercept + fit.slope * 1.0e6, -250.0e6 + 3.0e8, 1e-4);
  EXPECT_NEAR(fit.rSquared, 1.0, 1e-12);
  EXPECT_EQ(fit.count, 50u);
}

TEST(LineFit, RSquaredIsTheSquaredCorrelation) {
  const std::vector<double> x{0, 1, 2, 3, 4, 5};
  const std::vector<double> y{1.0, 2.9, 5.2, 6.8, 9.3, 10.7};
  const LineFit fit = fitLine(x, y);
  double mx = 2.5, my = 0, sxy = 0, sxx = 0, syy = 0;
  for (double v : y) my += v / 6.0;
  for (int i = 0; i < 6; ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  EXPECT_NEAR(fit.slope, sxy / sxx, 1e-12);
  EXPECT_NEAR(fit.rSquared, sxy * sxy / (sxx * syy), 1e-12);
  EXPECT_LT(fit.rSquared, 1.0);
}

TEST(LineFit, BadInputNamesTheProblem) {
  const std::vector<double> one{1.0};
  EXPECT_NE(errorOf([&] { fitLine(one, one); }).find("1 points given, at least 2"),
            std::string::npos);
  const std::vector<double> x{0, 1, 2, 3};
  std::vector<double> y{0, 1, 2, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_NE(errorOf([&] { fitLine(x, y); }).find("y[3] is nan"), std::string::npos);
  const std::vector<double> same{2, 2, 2};
  EXPECT_NE(errorOf([&] {
              fitLine(same, std::vector<double>{1, 2, 3});
            }).find("every x value is 2"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              fitLine(x, std::vector<double>{1, 2});
            }).find("4 x values but 2 y"),
            std::string::npos);
}

// A heap's surface, sampled as the highest granule in rings around the axis: a straight flank
// at a known angle with a little roughness, plus a few grains bouncing above it. The bisquare fit
// ignores the bouncers and gives the angle; a plain fit does not.
TEST(RobustLineFit, HeapFlankWithBouncingGrainsGivesItsAngle) {
  const double angle = 27.0;  // degrees
  const double slope = -std::tan(angle * std::numbers::pi / 180.0);
  std::mt19937_64 random(42);
  std::normal_distribution<double> roughness(0.0, 0.004);
  std::vector<double> r;
  std::vector<double> h;
  for (int i = 0; i < 60; ++i) {
    r.push_back(0.05 + 0.005 * i);
    h.push_back(0.4 + slope * r.back() + roughness(random));
  }
  const std::vector<int> bouncers{7, 19, 33, 34, 50, 58};
  for (int i : bouncers) h[std::size_t(i)] += 0.08;
  const RobustLineFit robust = fitLineRobust(r, h);
  const double robustAngle = std::atan(-robust.line.slope) * 180.0 / std::numbers::pi;
  const double plainAngle = std::atan(-fitLine(r, h).slope) * 180.0 / std::numbers::pi;
  EXPECT_NEAR(robustAngle, angle, 0.5);
  EXPECT_GT(std::abs(plainAngle - angle), 1.0) << "the bouncers should spoil a plain fit";
  for (int i : bouncers) EXPECT_EQ(robust.weights[std::size_t(i)], 0.0) << "point " << i;
  // The roughness alone leaves 1 − σ²/var(h) ≈ 0.99 of the variance explained.
  EXPECT_GT(robust.line.rSquared, 0.98);
  EXPECT_LT(robust.iterations, 100);
}

TEST(RobustLineFit, ExactLineIsKeptWhole) {
  const std::vector<double> x{0, 1, 2, 3, 4};
  const std::vector<double> y{1, 3, 5, 7, 9};
  const RobustLineFit fit = fitLineRobust(x, y);
  EXPECT_NEAR(fit.line.slope, 2.0, 1e-12);
  EXPECT_NEAR(fit.line.intercept, 1.0, 1e-12);
  for (double w : fit.weights) EXPECT_EQ(w, 1.0);
}

TEST(PowerLaw, ExactDataGivesItsParameters) {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> yOffset;
  for (int i = 0; i <= 8; ++i) {
    x.push_back(0.1 * i);
    yOffset.push_back(20.0 * std::pow(x.back(), 0.51) + 4.0);
  }
  for (int i = 1; i <= 8; ++i) y.push_back(3.0 * std::pow(x[std::size_t(i)], 0.51));
  const std::vector<double> positiveX(x.begin() + 1, x.end());
  const PowerLawFit plain = fitPowerLaw(positiveX, y);
  EXPECT_NEAR(plain.coefficient, 3.0, 1e-8);
  EXPECT_NEAR(plain.exponent, 0.51, 1e-8);
  EXPECT_EQ(plain.offset, 0.0);
  EXPECT_NEAR(plain.rSquared, 1.0, 1e-12);
  // With μ = 0 among the points (the paper's Fig. 22 starts there), the offset is fitted too.
  const PowerLawFit offset = fitPowerLaw(x, yOffset, PowerLawForm::WithOffset);
  EXPECT_NEAR(offset.coefficient, 20.0, 1e-6);
  EXPECT_NEAR(offset.exponent, 0.51, 1e-6);
  EXPECT_NEAR(offset.offset, 4.0, 1e-6);
}

TEST(PowerLaw, NoisyDataStaysNearItsParameters) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, 0.2);  // degrees
  std::vector<double> x;
  std::vector<double> y;
  for (int i = 1; i <= 16; ++i) {
    x.push_back(0.05 * i);
    y.push_back(25.0 * std::pow(x.back(), 0.51) + noise(random));
  }
  const PowerLawFit fit = fitPowerLaw(x, y);
  EXPECT_NEAR(fit.exponent, 0.51, 0.03);
  EXPECT_NEAR(fit.coefficient, 25.0, 0.8);
  EXPECT_GT(fit.rSquared, 0.99);
}

TEST(PowerLaw, BadInputNamesThePoint) {
  const std::vector<double> x{0.0, 0.1, 0.2};
  const std::vector<double> y{1.0, 2.0, 3.0};
  EXPECT_NE(errorOf([&] { fitPowerLaw(x, y); }).find("x[0] is 0"), std::string::npos);
  const std::vector<double> negativeY{1.0, -2.0, 3.0};
  const std::vector<double> positiveX{0.1, 0.2, 0.3};
  EXPECT_NE(errorOf([&] { fitPowerLaw(positiveX, negativeY); }).find("y[1] is -2"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { fitPowerLaw(x, y, PowerLawForm::WithOffset); }).find("at least 4"),
            std::string::npos);
}

TEST(Beverloo, PaperFitComesBackFromItsOwnCurve) {
  const std::vector<double> d{8, 10, 12, 14, 16, 18, 20, 22, 24};
  std::vector<double> w;
  for (double v : d) w.push_back(7.94 * std::pow(v - 4.107, 2.5));
  const BeverlooFit exact = fitBeverloo(d, w);
  EXPECT_NEAR(exact.c, 7.94, 1e-6);
  EXPECT_NEAR(exact.k, 4.107, 1e-6);
  EXPECT_NEAR(exact.rSquared, 1.0, 1e-12);

  // 2% scatter in the measured rates moves C and k only a little.
  std::mt19937_64 random(3);
  std::normal_distribution<double> scatter(1.0, 0.02);
  for (double& v : w) v *= scatter(random);
  const BeverlooFit noisy = fitBeverloo(d, w);
  EXPECT_NEAR(noisy.c, 7.94, 0.6);
  EXPECT_NEAR(noisy.k, 4.107, 0.5);
  EXPECT_GT(noisy.rSquared, 0.99);
}

TEST(Beverloo, RatesThatDoNotGrowWithTheOutletAreRefused) {
  const std::vector<double> d{8, 12, 16};
  EXPECT_NE(errorOf([&] {
              fitBeverloo(d, std::vector<double>{300, 200, 100});
            }).find("does not grow"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              fitBeverloo(d, std::vector<double>{300, 0, 100});
            }).find("flow rate [1] is 0"),
            std::string::npos);
}

}  // namespace
}  // namespace sandphys::analysis
