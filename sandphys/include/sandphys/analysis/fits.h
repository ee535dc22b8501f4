#pragma once

#include <cstddef>
#include <span>
#include <vector>

/// Curve fits for the validation experiments (Longmore et al. 2013, section 6): the steady flow
/// of an hourglass (a line), the surface of a heap (a robust line), the angle of repose against
/// friction (a power law) and flow rate against outlet size (Beverloo's law). Double precision
/// throughout; every function throws sandphys::InvalidArgument naming the function, the input and
/// the problem (too few points, a non-finite value and its index, mismatched lengths).
namespace sandphys::analysis {

/// y = slope · x + intercept.
struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  /// Coefficient of determination, 1 − SS_res / SS_tot, of the (weighted) fit; 1 when every y
  /// is equal and the line goes through them.
  double rSquared = 0.0;
  /// Points that took part.
  std::size_t count = 0;
};

/// Ordinary least squares. Needs at least 2 points and x values that are not all equal.
LineFit fitLine(std::span<const double> x, std::span<const double> y);

/// A line fitted with bisquare (Tukey biweight) weights, and the final weight of every point.
struct RobustLineFit {
  /// The line; its rSquared is the weighted one.
  LineFit line;
  /// Final weight of each input point, in [0, 1]: 0 for a point the fit rejected as an outlier.
  std::vector<double> weights;
  /// Reweighting rounds until the coefficients changed by less than 1e-10 (relative).
  int iterations = 0;
};

/// Iteratively reweighted least squares with bisquare weights w = (1 − u²)² for |u| < 1, else 0,
/// where u = r / (tuning · s · √(1 − h)): r the residual, h the point's leverage and s the robust
/// scale (median absolute deviation of the residuals from their median, / 0.6745). The default
/// tuning constant 4.685 keeps 95% efficiency for normal errors (as MATLAB's robustfit and
/// statsmodels' TukeyBiweight). Needs at least 3 points and x values that are not all equal.
RobustLineFit fitLineRobust(std::span<const double> x, std::span<const double> y,
                            double tuning = 4.685);

/// y = coefficient · x^exponent + offset.
struct PowerLawFit {
  double coefficient = 0.0;
  double exponent = 0.0;
  /// 0 unless fitted (PowerLawForm::WithOffset).
  double offset = 0.0;
  /// Of the fit in the data's own units (not in logarithms).
  double rSquared = 0.0;
};

/// Which power law fitPowerLaw fits.
enum class PowerLawForm {
  /// y = a x^b; needs every x > 0 and y > 0 (the starting guess is a line in log-log).
  NoOffset,
  /// y = a x^b + c; x ≥ 0 (a point at x = 0 sets the offset), at least 4 points.
  WithOffset,
};

/// Least squares in y (Levenberg-Marquardt, Eigen's unsupported module), started from the
/// log-log line through the points. Throws InvalidArgument when the fit does not converge.
PowerLawFit fitPowerLaw(std::span<const double> x, std::span<const double> y,
                        PowerLawForm form = PowerLawForm::NoOffset);

/// Beverloo's law for the discharge of grains through a round outlet, W = C (D − k)^{5/2}, with
/// the outlet diameter D and the empty annulus k both in particle diameters and W in grains per
/// second (the paper's Fig. 24 fit is C = 7.94, k = 4.107).
struct BeverlooFit {
  double c = 0.0;
  double k = 0.0;
  double rSquared = 0.0;
};

/// Least squares in W (Levenberg-Marquardt), started from the line through (D, W^{2/5}), whose
/// slope is C^{2/5} and whose root is k. Needs at least 3 points, every W > 0, and a fit with
/// k below the smallest D.
BeverlooFit fitBeverloo(std::span<const double> outletDiameters, std::span<const double> flowRates);

}  // namespace sandphys::analysis
