// Empirical distributions of measured values: Kaplan-Meier CDF, Freedman-Diaconis bins, the
// differenced density (Longmore et al. 2013, section 6.1.1).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "analysis/input_checks.h"
#include "sandphys/analysis/distributions.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

double EmpiricalCdf::operator()(double value) const {
  const auto after = std::upper_bound(x.begin(), x.end(), value);
  return after == x.begin() ? 0.0 : cdf[std::size_t(after - x.begin()) - 1];
}

EmpiricalCdf kaplanMeierCdf(std::span<const double> values, std::span<const bool> censored) {
  const char* function = "kaplanMeierCdf";
  detail::checkValues(function, "values", values, 1);
  if (!censored.empty() && censored.size() != values.size()) {
    throw InvalidArgument(std::string(function) + ": " + std::to_string(censored.size()) +
                          " censoring flags for " + std::to_string(values.size()) + " values");
  }
  const auto isCensored = [&](std::size_t i) { return !censored.empty() && censored[i]; };
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });

  EmpiricalCdf result;
  double survival = 1.0;
  std::size_t atRisk = values.size();
  for (std::size_t i = 0; i < order.size();) {
    const double value = values[order[i]];
    std::size_t events = 0;
    std::size_t here = 0;
    // Every value equal to this one: the events happen here, and the censored ones leave the
    // risk set after it (the usual convention: censored at t means survived t).
    for (; i + here < order.size() && values[order[i + here]] == value; ++here) {
      if (!isCensored(order[i + here])) ++events;
    }
    if (events > 0) {
      survival *= 1.0 - double(events) / double(atRisk);
      result.x.push_back(value);
      result.cdf.push_back(1.0 - survival);
    }
    atRisk -= here;
    i += here;
  }
  if (result.x.empty()) {
    throw InvalidArgument(std::string(function) + ": all " + std::to_string(values.size()) +
                          " values are censored; the distribution is unknown");
  }
  return result;
}

namespace {

// Quantile by linear interpolation between order statistics (numpy's default, R's type 7).
double quantile(const std::vector<double>& sorted, double p) {
  const double position = p * double(sorted.size() - 1);
  const std::size_t below = std::size_t(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - double(below)) * (sorted[above] - sorted[below]);
}

}  // namespace

double freedmanDiaconisWidth(std::span<const double> values) {
  detail::checkValues("freedmanDiaconisWidth", "values", values, 2);
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const double iqr = quantile(sorted, 0.75) - quantile(sorted, 0.25);
  return 2.0 * iqr / std::cbrt(double(sorted.size()));
}

Density densityFromCdf(const EmpiricalCdf& cdf, double binWidth) {
  const char* function = "densityFromCdf";
  if (cdf.x.empty() || cdf.x.size() != cdf.cdf.size()) {
    throw InvalidArgument(std::string(function) + ": the CDF is empty or its arrays differ");
  }
  if (!(binWidth > 0.0) || !std::isfinite(binWidth)) {
    throw InvalidArgument(std::string(function) + ": bin width " + detail::numberText(binWidth) +
                          " must be finite and > 0");
  }
  const double low = cdf.x.front();
  const double span = cdf.x.back() - low;
  // Enough bins that the last edge lies beyond the largest value, so that F there is complete.
  const std::size_t bins = std::size_t(std::floor(span / binWidth)) + 1;
  constexpr std::size_t kMaxBins = 10'000'000;
  if (bins > kMaxBins) {
    throw InvalidArgument(std::string(function) + ": bin width " + detail::numberText(binWidth) +
                          " over a range of " + detail::numberText(span) + " makes " +
                          std::to_string(bins) + " bins, more than " + std::to_string(kMaxBins));
  }
  Density density;
  density.edges.resize(bins + 1);
  for (std::size_t i = 0; i <= bins; ++i) density.edges[i] = low + double(i) * binWidth;
  density.centres.resize(bins);
  density.density.resize(bins);
  // F just below the first edge is 0: the smallest value's own step belongs to the first bin.
  double left = 0.0;
  for (std::size_t i = 0; i < bins; ++i) {
    const double right = cdf(density.edges[i + 1]);
    density.centres[i] = low + (double(i) + 0.5) * binWidth;
    density.density[i] = (right - left) / binWidth;
    left = right;
  }
  return density;
}

Density probabilityDensity(std::span<const double> values) {
  const double width = freedmanDiaconisWidth(values);
  if (!(width > 0.0)) {
    throw InvalidArgument(
        "probabilityDensity: the interquartile range of the " + std::to_string(values.size()) +
        " values is 0 (more than half of them are equal), so the Freedman-Diaconis bin width is "
        "0");
  }
  return densityFromCdf(kaplanMeierCdf(values), width);
}

std::vector<double> normalisedByMean(std::span<const double> values) {
  detail::checkValues("normalisedByMean", "values", values, 1);
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  if (!(mean > 0.0) || !std::isfinite(mean)) {
    throw InvalidArgument("normalisedByMean: the mean of the values is " +
                          detail::numberText(mean) + "; it must be finite and > 0");
  }
  std::vector<double> out(values.begin(), values.end());
  for (double& v : out) v /= mean;
  return out;
}

}  // namespace sandphys::analysis
