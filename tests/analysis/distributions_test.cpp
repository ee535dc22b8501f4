// Empirical distributions and their fits against samples of known distributions, and the
// Kaplan-Meier estimate against a hand-worked example.
#include <gtest/gtest.h>

#include <cmath>
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

double integral(const Density& density) {
  double sum = 0.0;
  for (std::size_t i = 0; i < density.density.size(); ++i) {
    sum += density.density[i] * (density.edges[i + 1] - density.edges[i]);
  }
  return sum;
}

TEST(KaplanMeier, WithoutCensoringItIsTheEmpiricalCdf) {
  const std::vector<double> values{3, 1, 2, 2};
  const EmpiricalCdf cdf = kaplanMeierCdf(values);
  ASSERT_EQ(cdf.x, (std::vector<double>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(cdf.cdf[0], 0.25);
  EXPECT_DOUBLE_EQ(cdf.cdf[1], 0.75);
  EXPECT_DOUBLE_EQ(cdf.cdf[2], 1.0);
  EXPECT_EQ(cdf(0.5), 0.0);
  EXPECT_EQ(cdf(2.5), 0.75);
  EXPECT_EQ(cdf(9.0), 1.0);
}

// Five values, the second and fourth censored (known only to be at least that large):
// S(1) = 4/5; at 3 three remain at risk, S = 4/5 · 2/3; at 5 one remains, S = 0.
TEST(KaplanMeier, CensoredValuesLeaveTheRiskSetWithoutAStep) {
  const std::vector<double> values{1, 2, 3, 4, 5};
  const bool censored[] = {false, true, false, true, false};
  const EmpiricalCdf cdf = kaplanMeierCdf(values, censored);
  ASSERT_EQ(cdf.x, (std::vector<double>{1, 3, 5}));
  EXPECT_DOUBLE_EQ(cdf.cdf[0], 0.2);
  EXPECT_DOUBLE_EQ(cdf.cdf[1], 1.0 - 0.8 * 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(cdf.cdf[2], 1.0);
  const bool all[] = {true, true, true, true, true};
  EXPECT_NE(errorOf([&] { kaplanMeierCdf(values, all); }).find("all 5 values are censored"),
            std::string::npos);
  const bool two[] = {true, false};
  EXPECT_NE(errorOf([&] { kaplanMeierCdf(values, two); }).find("2 censoring flags for 5"),
            std::string::npos);
}

TEST(FreedmanDiaconis, WidthOfOneToAHundred) {
  std::vector<double> values;
  for (int i = 1; i <= 100; ++i) values.push_back(i);
  // Quartiles 25.75 and 75.25 (linear interpolation), IQR 49.5.
  EXPECT_NEAR(freedmanDiaconisWidth(values), 2.0 * 49.5 / std::cbrt(100.0), 1e-12);
  const std::vector<double> mostlyEqual{1, 1, 1, 1, 1, 2};
  EXPECT_EQ(freedmanDiaconisWidth(mostlyEqual), 0.0);
  EXPECT_NE(errorOf([&] { probabilityDensity(mostlyEqual); }).find("interquartile range"),
            std::string::npos);
}

// Normalised contact forces of a loose pile are roughly exponential: P(f) = e^{-f}.
TEST(Density, ExponentialSamplesGiveBackTheirTail) {
  std::mt19937_64 random(11);
  std::exponential_distribution<double> draw(1.0);
  std::vector<double> values(200000);
  for (double& v : values) v = draw(random);
  const std::vector<double> f = normalisedByMean(values);
  const Density density = probabilityDensity(f);
  EXPECT_NEAR(integral(density), 1.0, 1e-12);
  const ExponentialFit fit = fitExponentialTail(density, {.from = 0.5, .to = 5.0});
  EXPECT_NEAR(fit.b, 1.0, 0.03);
  EXPECT_NEAR(fit.a, 1.0, 0.05);
  EXPECT_GT(fit.rSquared, 0.99);
}

// A half-normal of σ has P(f) = β e^{-α f²} with α = 1/(2σ²), β = 2/(σ√(2π)).
TEST(Density, HalfNormalSamplesGiveBackTheirGaussian) {
  const double sigma = 0.8;
  std::mt19937_64 random(12);
  std::normal_distribution<double> draw(0.0, sigma);
  std::vector<double> values(200000);
  for (double& v : values) v = std::abs(draw(random));
  const GaussianFit fit = fitGaussianTail(probabilityDensity(values), {.from = 0.2, .to = 2.5});
  EXPECT_NEAR(fit.alpha, 1.0 / (2.0 * sigma * sigma), 0.04);
  EXPECT_NEAR(fit.beta, 2.0 / (sigma * std::sqrt(2.0 * std::numbers::pi)), 0.04);
}

TEST(Density, TailFitsNeedTwoBinsInTheirRange) {
  const std::vector<double> values{0.1, 0.5, 0.9, 1.2, 1.6, 2.0, 2.1, 3.5};
  const Density density = probabilityDensity(values);
  EXPECT_NE(errorOf([&] {
              fitExponentialTail(density, {.from = 50.0, .to = 60.0});
            }).find("0 bins with a density > 0 in [50, 60]"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { fitGaussianTail(density, {.from = 2.0, .to = 1.0}); }).find("is empty"),
            std::string::npos);
}

// Forces under compression follow a gamma distribution (Table 4: shape 3.36, scale 0.30 for
// particles).
TEST(Gamma, MaximumLikelihoodGivesBackShapeAndScale) {
  std::mt19937_64 random(13);
  std::gamma_distribution<double> draw(3.36, 0.30);
  std::vector<double> values(100000);
  for (double& v : values) v = draw(random);
  const GammaFit fit = fitGamma(values);
  EXPECT_NEAR(fit.shape, 3.36, 0.05);
  EXPECT_NEAR(fit.scale, 0.30, 0.005);
  // The density it describes is normalised.
  double sum = 0.0;
  for (int i = 0; i < 200000; ++i) sum += gammaDensity(fit, (i + 0.5) * 1e-4) * 1e-4;
  EXPECT_NEAR(sum, 1.0, 1e-6);
  EXPECT_EQ(gammaDensity(fit, 0.0), 0.0);
}

TEST(Gamma, BadValuesAreRefused) {
  EXPECT_NE(errorOf([] {
              fitGamma(std::vector<double>{1.0, 0.0, 2.0});
            }).find("values[1] is 0"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              fitGamma(std::vector<double>{2.0, 2.0});
            }).find("are equal"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              normalisedByMean(std::vector<double>{-1.0, 0.5});
            }).find("mean of the values is -0.25"),
            std::string::npos);
}

}  // namespace
}  // namespace sandphys::analysis
