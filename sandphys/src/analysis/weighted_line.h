#pragma once

#include <span>

#include "sandphys/analysis/fits.h"

namespace sandphys::analysis::detail {

/// Weighted least squares line through the points (all weights ≥ 0, at least two points with a
/// weight > 0 at distinct x). Throws InvalidArgument "`function`: ..." when the x values of the
/// weighted points are all equal. Inputs already checked by the caller.
LineFit weightedLine(const char* function, std::span<const double> x, std::span<const double> y,
                     std::span<const double> weights);

}  // namespace sandphys::analysis::detail
