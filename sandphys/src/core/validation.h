#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "sandphys/error.h"

namespace sandphys::detail {

/// Formats a value the way error messages show it (NaN and infinities spelled out).
inline std::string formatValue(double value) {
  if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));  // counts and capacities: exact
  }
  std::ostringstream out;
  out.precision(7);  // settings are floats: show what the user typed, not float noise
  out << value;
  return out.str();
}

/// Throws InvalidArgument "<field> = <value> is invalid: <limit>" unless `ok`.
inline void require(bool ok, const std::string& field, double value, const std::string& limit) {
  if (!ok) {
    throw InvalidArgument(field + " = " + formatValue(value) + " is invalid: " + limit);
  }
}

inline void requirePositive(const std::string& field, double value, const char* unit) {
  require(std::isfinite(value) && value > 0.0, field, value,
          std::string("must be finite and > 0 ") + unit);
}

inline void requireNonNegative(const std::string& field, double value, const char* unit) {
  require(std::isfinite(value) && value >= 0.0, field, value,
          std::string("must be finite and >= 0 ") + unit);
}

inline void requireFinite(const std::string& field, double value) {
  require(std::isfinite(value), field, value, "must be finite");
}

}  // namespace sandphys::detail
