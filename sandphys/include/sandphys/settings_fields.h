#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sandphys/settings.h"

namespace sandphys {

/// One field of WorldSettings, stated once: the World's range checks, the recordings of the
/// samples ("world:KEY") and the viewer's controls read its name, unit, range and meaning here.
/// Checks that depend on other fields (the time step against the stiffness, listSkin against the
/// diameter, the derived particle capacity) stay with the code that derives them.
struct SettingField {
  enum class Kind { Real, Count, Flag, Law };

  const char* member;  ///< path below WorldSettings, as errors name it: "material.youngsModulus"
  const char* key;     ///< snake_case name in recordings: "youngs_modulus"
  const char* label;   ///< what a user interface calls it: "Young's modulus"
  const char* unit;    ///< SI unit ("Pa"), or "" for a plain number
  Kind kind;
  /// The accepted range of a Real or Count (Law: the enumerators); a bound is inclusive unless
  /// its open flag is set. Real fields must also be finite.
  double min;
  double max;
  bool minOpen;
  bool maxOpen;
  const char* help;  ///< one line: what it does, and what 0 means where 0 derives it

  float* (*real)(WorldSettings&) = nullptr;           ///< Kind::Real
  std::uint32_t* (*count)(WorldSettings&) = nullptr;  ///< Kind::Count
  bool* (*flag)(WorldSettings&) = nullptr;            ///< Kind::Flag
  ContactLaw* (*law)(WorldSettings&) = nullptr;       ///< Kind::Law

  /// The field's value as a double (a flag 0 or 1, a law its enumerator).
  double valueIn(const WorldSettings& settings) const;
  /// Whether `value` lies in [min, max] with the open bounds excluded (and, Real, is finite).
  bool accepts(double value) const;
  /// The range as an error states it: "must be finite and > 0 (Pa)", "must be in [0, 0.5)".
  std::string rangeText() const;
};

/// Every field of WorldSettings, in declaration order.
std::span<const SettingField> worldSettingFields();

/// The field with recording key `key`, or nullptr.
const SettingField* findWorldSettingField(std::string_view key);

}  // namespace sandphys
