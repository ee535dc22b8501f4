#pragma once

#include <concepts>
#include <sstream>
#include <string>
#include <string_view>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// Short text of a number for messages ("2.5", "0.1", "1e+06").
inline std::string numberText(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

namespace detail {
inline void appendPart(std::string& text, std::string_view part) {
  text += part;
}
template <std::integral T>
void appendPart(std::string& text, T value) {
  text += std::to_string(value);
}
template <std::floating_point T>
void appendPart(std::string& text, T value) {
  text += numberText(value);
}
}  // namespace detail

/// Throws InvalidArgument "`scene`: parts..." unless `ok`: text as it is, integers in full,
/// other numbers by numberText ("2.5", "1e+06").
template <class... Parts>
void require(bool ok, std::string_view scene, const Parts&... parts) {
  if (ok) return;
  std::string text(scene);
  text += ": ";
  (detail::appendPart(text, parts), ...);
  throw InvalidArgument(text);
}

}  // namespace sandphys::scenes::kit
