// Non-linear least squares fits: a power law (angle of repose against friction) and Beverloo's
// law (flow rate against outlet size). Levenberg-Marquardt from Eigen's unsupported module,
// started from the straight line each law becomes after a change of variables.
#include <unsupported/Eigen/LevenbergMarquardt>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "analysis/input_checks.h"
#include "sandphys/analysis/fits.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

namespace {

// A model y = f(x; p) with its gradient in p, as the residuals and Jacobian LM wants.
struct Model {
  std::function<double(double x, const Eigen::VectorXd& p)> value;
  // Writes the p.size() partial derivatives to grad.
  std::function<void(double x, const Eigen::VectorXd& p, double* grad)> gradient;
};

struct Residuals : Eigen::DenseFunctor<double> {
  Residuals(const Model& model, std::span<const double> x, std::span<const double> y, int params)
      : Eigen::DenseFunctor<double>(params, int(x.size())), m_model(model), m_x(x), m_y(y) {}

  int operator()(const InputType& p, ValueType& r) const {
    for (std::size_t i = 0; i < m_x.size(); ++i) {
      r[Eigen::Index(i)] = m_model.value(m_x[i], p) - m_y[i];
    }
    return 0;
  }
  int df(const InputType& p, JacobianType& jacobian) const {
    double grad[3];
    for (std::size_t i = 0; i < m_x.size(); ++i) {
      m_model.gradient(m_x[i], p, grad);
      for (Eigen::Index j = 0; j < p.size(); ++j) jacobian(Eigen::Index(i), j) = grad[j];
    }
    return 0;
  }

  const Model& m_model;
  std::span<const double> m_x;
  std::span<const double> m_y;
};

// Minimises Σ (f(x; p) − y)² from `start`; throws when it fails or leaves the finite numbers.
Eigen::VectorXd leastSquares(const char* function, const Model& model, std::span<const double> x,
                             std::span<const double> y, Eigen::VectorXd start) {
  Residuals residuals(model, x, y, int(start.size()));
  Eigen::LevenbergMarquardt<Residuals> solver(residuals);
  solver.setMaxfev(2000);
  const Eigen::LevenbergMarquardtSpace::Status status = solver.minimize(start);
  const bool failed = status == Eigen::LevenbergMarquardtSpace::ImproperInputParameters ||
                      status == Eigen::LevenbergMarquardtSpace::TooManyFunctionEvaluation;
  if (failed || !start.allFinite()) {
    throw InvalidArgument(std::string(function) + ": the least-squares fit did not converge " +
                          "(Levenberg-Marquardt status " + std::to_string(int(status)) +
                          "); the points do not follow the law");
  }
  return start;
}

double rSquared(const Model& model, const Eigen::VectorXd& p, std::span<const double> x,
                std::span<const double> y) {
  double mean = 0.0;
  for (double v : y) mean += v;
  mean /= double(y.size());
  double residual = 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - model.value(x[i], p);
    residual += r * r;
    total += (y[i] - mean) * (y[i] - mean);
  }
  return total > 0.0 ? 1.0 - residual / total : 1.0;
}

// x^b, with 0^b = 0 for b > 0 (a heap without friction at x = 0).
double power(double x, double b) {
  return x == 0.0 ? (b > 0.0 ? 0.0 : std::numeric_limits<double>::infinity()) : std::pow(x, b);
}

}  // namespace

PowerLawFit fitPowerLaw(std::span<const double> x, std::span<const double> y, PowerLawForm form) {
  const char* function = "fitPowerLaw";
  const bool withOffset = form == PowerLawForm::WithOffset;
  detail::checkPoints(function, x, y, withOffset ? 4 : 2);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (withOffset ? x[i] < 0.0 : x[i] <= 0.0) {
      throw InvalidArgument(std::string(function) + ": x[" + std::to_string(i) + "] is " +
                            detail::numberText(x[i]) + "; a power law needs x " +
                            (withOffset ? ">= 0" : "> 0"));
    }
    if (!withOffset && y[i] <= 0.0) {
      throw InvalidArgument(std::string(function) + ": y[" + std::to_string(i) + "] is " +
                            detail::numberText(y[i]) + "; y = a x^b without an offset needs y > 0");
    }
  }
  // Start: the offset just below the smallest y (so that every y − c > 0; with a > 0 that is the
  // point nearest x = 0),
  // then the line through (ln x, ln(y − c)).
  double offset = 0.0;
  if (withOffset) {
    const auto [low, high] = std::minmax_element(y.begin(), y.end());
    offset = *low - 1e-3 * (*high - *low);
  }
  std::vector<double> lx;
  std::vector<double> ly;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] > 0.0 && y[i] - offset > 0.0) {
      lx.push_back(std::log(x[i]));
      ly.push_back(std::log(y[i] - offset));
    }
  }
  Eigen::VectorXd p(withOffset ? 3 : 2);
  p[0] = 1.0;
  p[1] = 1.0;
  if (lx.size() >= 2 &&
      *std::max_element(lx.begin(), lx.end()) > *std::min_element(lx.begin(), lx.end())) {
    const LineFit line = fitLine(lx, ly);
    p[0] = std::exp(line.intercept);
    p[1] = line.slope;
  }
  if (withOffset) p[2] = offset;

  const Model model{[withOffset](double xi, const Eigen::VectorXd& q) {
                      return q[0] * power(xi, q[1]) + (withOffset ? q[2] : 0.0);
                    },
                    [withOffset](double xi, const Eigen::VectorXd& q, double* g) {
                      const double xb = power(xi, q[1]);
                      g[0] = xb;
                      g[1] = xi > 0.0 ? q[0] * xb * std::log(xi) : 0.0;
                      if (withOffset) g[2] = 1.0;
                    }};
  p = leastSquares(function, model, x, y, p);
  PowerLawFit fit;
  fit.coefficient = p[0];
  fit.exponent = p[1];
  fit.offset = withOffset ? p[2] : 0.0;
  fit.rSquared = rSquared(model, p, x, y);
  return fit;
}

BeverlooFit fitBeverloo(std::span<const double> outletDiameters,
                        std::span<const double> flowRates) {
  const char* function = "fitBeverloo";
  detail::checkPoints(function, outletDiameters, flowRates, 3);
  std::vector<double> root(flowRates.size());
  for (std::size_t i = 0; i < flowRates.size(); ++i) {
    if (!(flowRates[i] > 0.0)) {
      throw InvalidArgument(std::string(function) + ": flow rate [" + std::to_string(i) + "] is " +
                            detail::numberText(flowRates[i]) +
                            " grains/s; Beverloo's law needs every rate > 0");
    }
    root[i] = std::pow(flowRates[i], 0.4);
  }
  // W^{2/5} = C^{2/5} (D − k): a line with slope C^{2/5} and root k.
  const LineFit line = fitLine(outletDiameters, root);
  if (!(line.slope > 0.0)) {
    throw InvalidArgument(std::string(function) +
                          ": the flow rate does not grow with the outlet diameter (slope of "
                          "W^(2/5) against D is " +
                          detail::numberText(line.slope) + ")");
  }
  Eigen::VectorXd p(2);
  p[0] = std::pow(line.slope, 2.5);
  p[1] = -line.intercept / line.slope;
  const Model model{[](double d, const Eigen::VectorXd& q) {
                      return q[0] * std::pow(std::max(d - q[1], 0.0), 2.5);
                    },
                    [](double d, const Eigen::VectorXd& q, double* g) {
                      const double gap = std::max(d - q[1], 0.0);
                      g[0] = std::pow(gap, 2.5);
                      g[1] = -2.5 * q[0] * std::pow(gap, 1.5);
                    }};
  p = leastSquares(function, model, outletDiameters, flowRates, p);
  const double smallest = *std::min_element(outletDiameters.begin(), outletDiameters.end());
  if (!(p[1] < smallest)) {
    throw InvalidArgument(std::string(function) + ": the fit puts k = " + detail::numberText(p[1]) +
                          " at or above the smallest outlet D = " + detail::numberText(smallest) +
                          "; the points do not follow the law");
  }
  return {.c = p[0], .k = p[1], .rSquared = rSquared(model, p, outletDiameters, flowRates)};
}

}  // namespace sandphys::analysis
