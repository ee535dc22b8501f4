#include "scenes/scene_parameters.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <type_traits>
#include <vector>

namespace sandphys::scenes {

namespace {

std::string rangeText(const SceneParameter& parameter) {
  std::ostringstream out;
  out << "[" << parameter.min << ", " << parameter.max << "]";
  return out.str();
}

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

[[noreturn]] void fail(const SceneParameter& parameter, std::string_view text,
                       std::string_view why) {
  throw InvalidArgument("scene parameter '" + parameter.name + "': value '" + std::string(text) +
                        "' " + std::string(why) + " (valid range " + rangeText(parameter) + ")");
}

// Parses one number of type T from the whole of `text`; from_chars, because it neither reads the
// locale nor accepts trailing garbage or a sign on unsigned types.
template <typename T>
T parseNumber(const SceneParameter& parameter, std::string_view text) {
  T value{};
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) fail(parameter, text, "is not a valid number");
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) fail(parameter, text, "is not finite");
  }
  if (!inRange(static_cast<double>(value), parameter)) fail(parameter, text, "is out of range");
  return value;
}

Count3 parseCount3(const SceneParameter& parameter, std::string_view text) {
  Count3 counts{};
  std::size_t component = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t next = text.find_first_of(", x", pos);
    const std::string_view token = text.substr(pos, next - pos);
    if (!token.empty()) {
      if (component == counts.size()) fail(parameter, text, "has more than three counts");
      try {
        counts[component++] = parseNumber<std::uint32_t>(parameter, token);
      } catch (const InvalidArgument&) {
        // Name the whole value, not only the bad count, so that the user finds it.
        fail(parameter, text, "has a count that is not a whole number in range");
      }
    }
    if (next == std::string_view::npos) break;
    pos = next + 1;
  }
  if (component != counts.size()) fail(parameter, text, "needs three counts, e.g. 8,8,4");
  return counts;
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
      out << " is out of range " << rangeText(parameter) << " (" << parameter.help << ")";
    }
    throw InvalidArgument(out.str());
  }
}

void useTestSize(Scene& scene) {
  for (const SceneParameter& parameter : scene.parameters()) {
    if (parameter.name == "batch" || parameter.name == "block" || parameter.name == "berm" ||
        parameter.name == "bed") {
      setSceneParameter(scene, parameter.name, "4,2,4");
    } else if (parameter.name == "granules") {
      setSceneParameter(scene, parameter.name, "32");
    } else if (parameter.name == "layers") {
      setSceneParameter(scene, parameter.name, "2");
    }
  }
}

void setSceneParameter(Scene& scene, std::string_view name, std::string_view text) {
  std::vector<SceneParameter> parameters = scene.parameters();
  for (const SceneParameter& parameter : parameters) {
    if (parameter.name != name) continue;
    std::visit(
        [&](auto* target) {
          using T = std::remove_pointer_t<decltype(target)>;
          if constexpr (std::is_same_v<T, Count3>) {
            *target = parseCount3(parameter, text);
          } else if constexpr (std::is_same_v<T, std::string>) {
            if (text.empty()) {
              throw InvalidArgument("scene parameter '" + parameter.name + "' is empty (" +
                                    parameter.help + ")");
            }
            *target = std::string(text);
          } else {
            *target = parseNumber<T>(parameter, text);
          }
        },
        parameter.value);
    return;
  }
  std::string known;
  for (const SceneParameter& parameter : parameters) {
    known += known.empty() ? "" : ", ";
    known += parameter.name;
  }
  throw InvalidArgument("scene '" + std::string(scene.name()) + "' has no parameter '" +
                        std::string(name) + "' (it has: " + (known.empty() ? "none" : known) + ")");
}

std::string formatSceneParameter(const SceneParameter& parameter) {
  return std::visit(
      [](auto* value) -> std::string {
        using T = std::remove_pointer_t<decltype(value)>;
        std::ostringstream out;
        if constexpr (std::is_same_v<T, Count3>) {
          out << (*value)[0] << ',' << (*value)[1] << ',' << (*value)[2];
        } else if constexpr (std::is_same_v<T, float>) {
          // The shortest text that reads back to the same float: recordings keep parameters as
          // text and must rebuild the scene bit for bit.
          char text[32];
          const auto result = std::to_chars(text, text + sizeof text, *value);
          out << std::string_view(text, std::size_t(result.ptr - text));
        } else {
          out << *value;
        }
        return out.str();
      },
      parameter.value);
}

}  // namespace sandphys::scenes
