#include "analysis/input_checks.h"

#include <cmath>
#include <sstream>

#include "sandphys/error.h"

namespace sandphys::analysis::detail {

namespace {

void checkFinite(const char* function, const char* name, std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidArgument(std::string(function) + ": " + name + "[" + std::to_string(i) +
                            "] is " + numberText(values[i]) + ", not a finite number");
    }
  }
}

[[noreturn]] void tooFew(const char* function, std::size_t count, const char* what,
                         std::size_t minCount) {
  throw InvalidArgument(std::string(function) + ": " + std::to_string(count) + " " + what +
                        " given, at least " + std::to_string(minCount) + " needed");
}

}  // namespace

std::string numberText(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

void checkValues(const char* function, const char* name, std::span<const double> values,
                 std::size_t minCount) {
  if (values.size() < minCount) tooFew(function, values.size(), "values", minCount);
  checkFinite(function, name, values);
}

void checkPoints(const char* function, std::span<const double> x, std::span<const double> y,
                 std::size_t minCount) {
  if (x.size() != y.size()) {
    throw InvalidArgument(std::string(function) + ": " + std::to_string(x.size()) +
                          " x values but " + std::to_string(y.size()) + " y values");
  }
  if (x.size() < minCount) tooFew(function, x.size(), "points", minCount);
  checkFinite(function, "x", x);
  checkFinite(function, "y", y);
}

}  // namespace sandphys::analysis::detail
