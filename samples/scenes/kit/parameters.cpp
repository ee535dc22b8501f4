#include "scenes/kit/parameters.h"

#include <sstream>
#include <type_traits>

namespace sandphys::scenes::kit {

namespace {

bool inRange(double value, const SceneParameter& parameter) {
  return value >= parameter.min && value <= parameter.max;
}

bool valid(const SceneParameter& parameter) {
  return std::visit(
      [&](auto* value) {
        using T = std::remove_pointer_t<decltype(value)>;
        if constexpr (std::is_same_v<T, Count3>) {
          for (std::uint32_t count : *value) {
            if (!inRange(count, parameter)) return false;
          }
          return true;
        } else if constexpr (std::is_same_v<T, std::string>) {
          return !value->empty();
        } else {
          return inRange(static_cast<double>(*value), parameter);
        }
      },
      parameter.value);
}

}  // namespace

void checkRanges(std::string_view scene, std::span<const SceneParameter> parameters) {
  for (const SceneParameter& parameter : parameters) {
    if (valid(parameter)) continue;
    std::ostringstream out;
    out << scene << ": parameter '" << parameter.name << "' = " << formatSceneParameter(parameter);
    if (std::holds_alternative<std::string*>(parameter.value)) {
      out << " is empty (" << parameter.help << ")";
    } else {
      out << " is out of range [" << parameter.min << ", " << parameter.max << "] ("
          << parameter.help << ")";
    }
    throw InvalidArgument(out.str());
  }
}

}  // namespace sandphys::scenes::kit
