// Force-force correlation, contact angles and weak/strong networks of a packing's contacts.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "analysis/input_checks.h"
#include "sandphys/analysis/contacts.h"
#include "sandphys/analysis/distributions.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

namespace {

void requirePositive(const char* function, const char* name, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InvalidArgument(std::string(function) + ": " + name + " is " + detail::numberText(value) +
                          "; it must be finite and > 0");
  }
}

void requireFinite(const char* function, const char* name, std::span<const Vec3> points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw InvalidArgument(std::string(function) + ": " + name + "[" + std::to_string(i) +
                            "] is (" + detail::numberText(p.x) + ", " + detail::numberText(p.y) +
                            ", " + detail::numberText(p.z) + "), not a finite vector");
    }
  }
}

}  // namespace

ForceCorrelation forceCorrelation(std::span<const Vec3> points, std::span<const double> forces,
                                  double binWidth, double maxDistance) {
  const char* function = "forceCorrelation";
  requirePositive(function, "binWidth", binWidth);
  requirePositive(function, "maxDistance", maxDistance);
  if (points.size() != forces.size()) {
    throw InvalidArgument(std::string(function) + ": " + std::to_string(points.size()) +
                          " points but " + std::to_string(forces.size()) + " forces");
  }
  detail::checkValues(function, "forces", forces, 2);
  requireFinite(function, "points", points);
  double mean = 0.0;
  for (double f : forces) mean += f;
  mean /= double(forces.size());
  requirePositive(function, "the mean force", mean);

  const auto bins = static_cast<std::size_t>(std::ceil(maxDistance / binWidth));
  ForceCorrelation result;
  std::vector<double> products(bins, 0.0);
  result.pairs.assign(bins, 0);
  // Sorted by x, so that the inner loop stops at the first point too far along x.
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return points[a].x < points[b].x; });
  const double reach2 = maxDistance * maxDistance;
  for (std::size_t a = 0; a < order.size(); ++a) {
    const Vec3& p = points[order[a]];
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const Vec3& q = points[order[b]];
      const double dx = double(q.x) - p.x;
      if (dx >= maxDistance) break;
      const double dy = double(q.y) - p.y;
      const double dz = double(q.z) - p.z;
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= reach2) continue;
      const auto bin = std::min(bins - 1, static_cast<std::size_t>(std::sqrt(r2) / binWidth));
      products[bin] += forces[order[a]] * forces[order[b]];
      ++result.pairs[bin];
    }
  }
  for (std::size_t k = 0; k < bins; ++k) {
    result.distance.push_back((double(k) + 0.5) * binWidth);
    result.correlation.push_back(
        result.pairs[k] ? products[k] / double(result.pairs[k]) / (mean * mean) : 0.0);
  }
  return result;
}

AngleDistribution contactAngles(std::span<const Vec3> normals, int bins) {
  const char* function = "contactAngles";
  if (bins < 1) {
    throw InvalidArgument(std::string(function) + ": bins is " + std::to_string(bins) +
                          "; it must be >= 1");
  }
  if (normals.empty()) throw InvalidArgument(std::string(function) + ": no normals given");
  requireFinite(function, "normals", normals);
  const double width = 90.0 / bins;
  std::vector<double> counts(static_cast<std::size_t>(bins), 0.0);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const Vec3& n = normals[i];
    const double horizontal = std::hypot(double(n.x), double(n.z));
    const double vertical = std::abs(double(n.y));
    if (horizontal == 0.0 && vertical == 0.0) {
      throw InvalidArgument(std::string(function) + ": normals[" + std::to_string(i) + "] is zero");
    }
    const double elevation = std::atan2(vertical, horizontal) * 180.0 / std::numbers::pi;
    const auto bin =
        std::min<std::size_t>(counts.size() - 1, static_cast<std::size_t>(elevation / width));
    counts[bin] += 1.0;
  }
  AngleDistribution result;
  const double degree = std::numbers::pi / 180.0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const double lo = double(k) * width;
    result.degrees.push_back(lo + 0.5 * width);
    result.density.push_back(counts[k] / double(normals.size()) / width);
    // Uniform directions: the elevation's density is cos(θ) (per radian), so a bin holds
    // sin(hi) − sin(lo) of them.
    result.isotropic.push_back((std::sin((lo + width) * degree) - std::sin(lo * degree)) / width);
  }
  return result;
}

NetworkFractions networkFractions(std::span<const double> forces, double step,
                                  double maxThreshold) {
  const char* function = "networkFractions";
  requirePositive(function, "step", step);
  if (!(maxThreshold >= 0.0) || !std::isfinite(maxThreshold)) {
    throw InvalidArgument(std::string(function) + ": maxThreshold is " +
                          detail::numberText(maxThreshold) + "; it must be finite and >= 0");
  }
  const std::vector<double> f = normalisedByMean(forces);
  double total = 0.0;
  for (double v : f) total += v;
  NetworkFractions result;
  const auto steps = static_cast<std::size_t>(std::floor(maxThreshold / step + 1e-9));
  for (std::size_t k = 0; k <= steps; ++k) {
    const double cut = double(k) * step;
    double count = 0.0;
    double carried = 0.0;
    for (double v : f) {
      if (v > cut) {
        count += 1.0;
        carried += v;
      }
    }
    result.threshold.push_back(cut);
    result.contacts.push_back(count / double(f.size()));
    result.force.push_back(carried / total);
  }
  return result;
}

}  // namespace sandphys::analysis
