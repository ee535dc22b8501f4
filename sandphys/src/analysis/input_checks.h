#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace sandphys::analysis::detail {

/// Throws InvalidArgument "`function`: ..." unless `values` has at least `minCount` entries and
/// every one is finite (naming the first bad one as name[index] and its value).
void checkValues(const char* function, const char* name, std::span<const double> values,
                 std::size_t minCount);

/// The same for a series of points (x[i], y[i]): equal lengths, at least `minCount`, all finite.
void checkPoints(const char* function, std::span<const double> x, std::span<const double> y,
                 std::size_t minCount);

/// Shortest round-trip text of a number, for messages.
std::string numberText(double value);

}  // namespace sandphys::analysis::detail
