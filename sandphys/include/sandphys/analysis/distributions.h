#pragma once

#include <cstddef>
#include <span>
#include <vector>

/// Probability distributions of measured values (contact forces normalised by their mean), made
/// the way Longmore et al. 2013 (section 6.1.1) make them: the Kaplan-Meier estimate of the
/// cumulative distribution, binned by the Freedman-Diaconis rule and differenced into a density;
/// then the exponential and Gaussian fits to its tail and a gamma fit to the values (their
/// Table 4). Double precision; bad input throws sandphys::InvalidArgument naming the function and
/// the problem.
namespace sandphys::analysis {

/// A step function: F(x) = probability of a value ≤ x, for x at each distinct value.
struct EmpiricalCdf {
  /// Distinct values, ascending.
  std::vector<double> x;
  /// F at each x, non-decreasing, in (0, 1].
  std::vector<double> cdf;

  /// F at any point: 0 below the first value, the step's value between two values.
  double operator()(double value) const;
};

/// The Kaplan-Meier estimate of the cumulative distribution of `values`. `censored` (empty, or
/// one flag per value) marks values known only to be at least that large (a contact still
/// loading when it was recorded, say); with no censoring the estimate is the plain empirical
/// CDF. Needs at least one value (uncensored), every value finite.
EmpiricalCdf kaplanMeierCdf(std::span<const double> values, std::span<const bool> censored = {});

/// The Freedman-Diaconis bin width 2 · IQR · n^{-1/3} (IQR the interquartile range, quartiles by
/// linear interpolation). Needs at least 2 values; 0 when more than half the values are equal.
double freedmanDiaconisWidth(std::span<const double> values);

/// A probability density sampled on equal bins.
struct Density {
  /// Bin edges, ascending, one more than there are bins.
  std::vector<double> edges;
  /// Bin centres.
  std::vector<double> centres;
  /// Density in each bin: (F(right edge) − F(left edge)) / width; it integrates to 1.
  std::vector<double> density;
};

/// The density of a CDF on bins of `binWidth` from its smallest to past its largest value.
Density densityFromCdf(const EmpiricalCdf& cdf, double binWidth);

/// The paper's procedure in one call: Kaplan-Meier CDF, Freedman-Diaconis bins, differenced.
/// Needs at least 2 values that are not mostly equal (a bin width > 0).
Density probabilityDensity(std::span<const double> values);

/// P(f) = a · exp(−b f), fitted to a density's tail.
struct ExponentialFit {
  double a = 0.0;
  double b = 0.0;
  /// Of the line through (f, ln P), the space the fit is made in.
  double rSquared = 0.0;
};

/// P(f) = beta · exp(−alpha f²), fitted to a density's tail.
struct GaussianFit {
  double beta = 0.0;
  double alpha = 0.0;
  /// Of the line through (f², ln P).
  double rSquared = 0.0;
};

/// The part of a density a tail fit uses: bins whose centre lies in [from, to] and whose density
/// is above zero (an empty bin has no logarithm).
struct FitRange {
  double from = 1.0;
  double to = 1.0e300;
};

/// Least squares line through (f, ln P) of the bins in `range`. Needs 2 such bins.
ExponentialFit fitExponentialTail(const Density& density, FitRange range = {});

/// Least squares line through (f², ln P) of the bins in `range`. Needs 2 such bins.
GaussianFit fitGaussianTail(const Density& density, FitRange range = {});

/// Gamma distribution P(f) = f^{a−1} exp(−f / b) / (Γ(a) b^a): shape a, scale b (mean a·b).
struct GammaFit {
  double shape = 0.0;
  double scale = 0.0;
};

/// Maximum likelihood (as MATLAB's gamfit): a solves ln a − ψ(a) = ln(mean) − mean(ln f) by
/// Newton's method, b = mean / a. Needs at least 2 values, every one > 0, not all equal.
GammaFit fitGamma(std::span<const double> values);

/// The gamma density at f for `fit`.
double gammaDensity(const GammaFit& fit, double f);

/// `values` divided by their mean (the paper's normalised forces f = F / ⟨F⟩). Needs a finite
/// positive mean.
std::vector<double> normalisedByMean(std::span<const double> values);

}  // namespace sandphys::analysis
