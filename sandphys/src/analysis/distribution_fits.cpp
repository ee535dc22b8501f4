// Fits to force distributions (the paper's Table 4): exponential and Gaussian lines through the
// logarithm of a density's tail, and the gamma distribution by maximum likelihood.
#include <unsupported/Eigen/SpecialFunctions>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/input_checks.h"
#include "analysis/weighted_line.h"
#include "sandphys/analysis/distributions.h"
#include "sandphys/analysis/fits.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

namespace {

// The line through (transform(f), ln P) of the bins in `range` with P > 0.
LineFit logDensityLine(const char* function, const Density& density, FitRange range,
                       double (*transform)(double)) {
  if (!(range.from <= range.to)) {
    throw InvalidArgument(std::string(function) + ": fit range [" + detail::numberText(range.from) +
                          ", " + detail::numberText(range.to) + "] is empty");
  }
  std::vector<double> x;
  std::vector<double> y;
  for (std::size_t i = 0; i < density.centres.size(); ++i) {
    const double f = density.centres[i];
    if (f >= range.from && f <= range.to && density.density[i] > 0.0) {
      x.push_back(transform(f));
      y.push_back(std::log(density.density[i]));
    }
  }
  if (x.size() < 2) {
    throw InvalidArgument(std::string(function) + ": " + std::to_string(x.size()) +
                          " bins with a density > 0 in [" + detail::numberText(range.from) + ", " +
                          detail::numberText(range.to) + "], at least 2 needed");
  }
  const std::vector<double> ones(x.size(), 1.0);
  return detail::weightedLine(function, x, y, ones);
}

double identity(double f) {
  return f;
}

double square(double f) {
  return f * f;
}

double digamma(double a) {
  return Eigen::numext::digamma(a);
}

double trigamma(double a) {
  return Eigen::numext::polygamma(1.0, a);
}

}  // namespace

ExponentialFit fitExponentialTail(const Density& density, FitRange range) {
  const LineFit line = logDensityLine("fitExponentialTail", density, range, &identity);
  return {.a = std::exp(line.intercept), .b = -line.slope, .rSquared = line.rSquared};
}

GaussianFit fitGaussianTail(const Density& density, FitRange range) {
  const LineFit line = logDensityLine("fitGaussianTail", density, range, &square);
  return {.beta = std::exp(line.intercept), .alpha = -line.slope, .rSquared = line.rSquared};
}

GammaFit fitGamma(std::span<const double> values) {
  const char* function = "fitGamma";
  detail::checkValues(function, "values", values, 2);
  double mean = 0.0;
  double meanLog = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] > 0.0)) {
      throw InvalidArgument(std::string(function) + ": values[" + std::to_string(i) + "] is " +
                            detail::numberText(values[i]) +
                            "; a gamma distribution has only values > 0");
    }
    mean += values[i];
    meanLog += std::log(values[i]);
  }
  mean /= double(values.size());
  meanLog /= double(values.size());
  // s > 0 by Jensen's inequality unless every value is equal.
  const double s = std::log(mean) - meanLog;
  if (!(s > 1e-14)) {
    throw InvalidArgument(std::string(function) + ": all " + std::to_string(values.size()) +
                          " values are equal; the shape is unbounded");
  }
  // Minka's closed-form start is within 1.5% of the root; Newton on ln a − ψ(a) = s then
  // converges in a few steps (the function is convex and decreasing in a).
  double a = (3.0 - s + std::sqrt((s - 3.0) * (s - 3.0) + 24.0 * s)) / (12.0 * s);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = std::log(a) - digamma(a) - s;
    const double slope = 1.0 / a - trigamma(a);
    const double next = a - f / slope;
    const double step = std::abs(next - a);
    a = next > 0.0 ? next : 0.5 * a;
    if (step <= 1e-13 * a) break;
  }
  return {.shape = a, .scale = mean / a};
}

double gammaDensity(const GammaFit& fit, double f) {
  if (!(f > 0.0)) return 0.0;
  return std::exp((fit.shape - 1.0) * std::log(f) - f / fit.scale - std::lgamma(fit.shape) -
                  fit.shape * std::log(fit.scale));
}

}  // namespace sandphys::analysis
