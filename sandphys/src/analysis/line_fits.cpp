// Ordinary and bisquare-weighted least squares lines (the hourglass's steady discharge, a heap's
// surface).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analysis/input_checks.h"
#include "analysis/weighted_line.h"
#include "sandphys/analysis/fits.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

namespace detail {

LineFit weightedLine(const char* function, std::span<const double> x, std::span<const double> y,
                     std::span<const double> weights) {
  double sw = 0.0;
  double mx = 0.0;
  double my = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sw += weights[i];
    mx += weights[i] * x[i];
    my += weights[i] * y[i];
    if (weights[i] > 0.0) ++count;
  }
  if (!(sw > 0.0)) throw InvalidArgument(std::string(function) + ": every weight is zero");
  mx /= sw;
  my /= sw;
  // Centred sums: the raw-moment form loses every digit when x is far from 0 (times in s since
  // a run began, say).
  double sxx = 0.0;
  double sxy = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mx;
    const double dy = y[i] - my;
    sxx += weights[i] * dx * dx;
    sxy += weights[i] * dx * dy;
    syy += weights[i] * dy * dy;
  }
  if (!(sxx > 0.0)) {
    throw InvalidArgument(std::string(function) + ": every x value is " + numberText(mx) +
                          "; a line needs at least two different x values");
  }
  LineFit fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  fit.count = count;
  double residual = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - (fit.intercept + fit.slope * x[i]);
    residual += weights[i] * r * r;
  }
  fit.rSquared = syy > 0.0 ? 1.0 - residual / syy : 1.0;
  return fit;
}

}  // namespace detail

LineFit fitLine(std::span<const double> x, std::span<const double> y) {
  detail::checkPoints("fitLine", x, y, 2);
  const std::vector<double> ones(x.size(), 1.0);
  return detail::weightedLine("fitLine", x, y, ones);
}

namespace {

double median(std::vector<double> values) {
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(half), values.end());
  const double upper = values[half];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + std::ptrdiff_t(half)));
}

}  // namespace

RobustLineFit fitLineRobust(std::span<const double> x, std::span<const double> y, double tuning) {
  const char* function = "fitLineRobust";
  detail::checkPoints(function, x, y, 3);
  if (!(tuning > 0.0) || !std::isfinite(tuning)) {
    throw InvalidArgument(std::string(function) + ": tuning constant " +
                          detail::numberText(tuning) + " must be finite and > 0");
  }
  const std::size_t n = x.size();
  RobustLineFit result;
  result.weights.assign(n, 1.0);
  LineFit fit = detail::weightedLine(function, x, y, result.weights);

  // Leverage of each point in the unweighted design (1, x): a point far out along x pulls the
  // line towards itself, so its residual understates how far off it is.
  double mx = 0.0;
  for (double v : x) mx += v;
  mx /= double(n);
  double sxx = 0.0;
  for (double v : x) sxx += (v - mx) * (v - mx);
  std::vector<double> adjust(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double h = 1.0 / double(n) + (x[i] - mx) * (x[i] - mx) / sxx;
    adjust[i] = 1.0 / std::sqrt(std::max(1.0 - h, 1e-12));
  }

  constexpr int kMaxIterations = 100;
  std::vector<double> residuals(n);
  std::vector<double> magnitudes(n);
  for (result.iterations = 1; result.iterations <= kMaxIterations; ++result.iterations) {
    for (std::size_t i = 0; i < n; ++i) {
      residuals[i] = (y[i] - (fit.intercept + fit.slope * x[i])) * adjust[i];
      magnitudes[i] = std::abs(residuals[i]);
    }
    // Robust scale: the median absolute residual of a normal sample is 0.6745 σ.
    double scale = median(magnitudes) / 0.6745;
    if (!(scale > 0.0)) {
      // More than half the points lie on the line: it is exact for them, and the rest are
      // outliers of any size.
      for (std::size_t i = 0; i < n; ++i) result.weights[i] = magnitudes[i] == 0.0 ? 1.0 : 0.0;
      fit = detail::weightedLine(function, x, y, result.weights);
      break;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double u = residuals[i] / (tuning * scale);
      result.weights[i] = std::abs(u) < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
    const LineFit next = detail::weightedLine(function, x, y, result.weights);
    const double change =
        std::abs(next.slope - fit.slope) + std::abs(next.intercept - fit.intercept);
    const double size = std::abs(fit.slope) + std::abs(fit.intercept);
    fit = next;
    if (change <= 1e-10 * size) break;
  }
  result.iterations = std::min(result.iterations, kMaxIterations);
  result.line = fit;
  return result;
}

}  // namespace sandphys::analysis
