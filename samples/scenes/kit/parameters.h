#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scenes/kit/checks.h"
#include "scenes/kit/settings.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// Where a parameter lives in a scene's Config.
template <class Config>
using Member = std::variant<std::uint32_t Config::*, std::uint64_t Config::*, float Config::*,
                            Count3 Config::*, std::string Config::*>;

/// Everything about one tunable value of a scene, said once: the command line, the range check,
/// recordings, goldens and the viewer's widgets all come from a scene's table of these (the
/// default is the Config member's initialiser).
template <class Config>
struct Param {
  /// kebab-case name on the command line and in the viewer ("pour-height").
  std::string_view name;
  Member<Config> member;
  /// Unit of the value ("d" for particle diameters, "m", "s", "m/s", "deg"); empty for counts.
  std::string_view unit;
  /// Valid range (of each component for Count3; not used for text).
  double min;
  double max;
  /// What the value does, one line without the unit.
  std::string_view help;
};

/// The SceneParameters of `table` bound to `config` (help and unit joined for --help and
/// tooltips).
template <class Config>
std::vector<SceneParameter> bind(std::span<const Param<Config>> table, Config& config) {
  std::vector<SceneParameter> out;
  out.reserve(table.size());
  for (const Param<Config>& row : table) {
    std::string help(row.help);
    if (!row.unit.empty()) help += ", " + std::string(row.unit);
    std::visit(
        [&](auto member) {
          out.push_back(
              {std::string(row.name), std::move(help), &(config.*member), row.min, row.max});
        },
        row.member);
  }
  return out;
}

// Rows that many scenes share, so that their name, range and help are said once.

/// Largest 64-bit seed, as the range's upper end.
inline constexpr double kMaxSeed = 1.8446744073709552e19;

template <class C>
Param<C> diameterParam(float C::*member) {
  return {"diameter", member, "m", 1e-4, 1.0, "particle diameter d"};
}
template <class C>
Param<C> seedParam(std::uint64_t C::*member) {
  return {"seed", member, "", 0.0, kMaxSeed, "random seed of the granules: same seed, same start"};
}
template <class C>
Param<C> frictionParam(float C::*member) {
  return {"friction", member, "", 0.0, 10.0, "Coulomb friction coefficient of every contact"};
}
template <class C>
Param<C> restitutionParam(float C::*member) {
  return {"restitution", member, "", 0.01, 1.0, "coefficient of restitution of every impact"};
}
/// The help of "youngs-modulus", with the overlap an auto modulus allows (settings.h).
inline const std::string kYoungsModulusHelp =
    "Young's modulus of the grains (0: auto, stiff enough that two grains meeting at the scene's "
    "speed guard overlap by " +
    numberText(kScenePeakOverlap) + " d)";
template <class C>
Param<C> youngsModulusParam(float C::*member) {
  return {"youngs-modulus", member, "Pa", 0.0, 1e12, kYoungsModulusHelp};
}
template <class C>
Param<C> stepsPerContactParam(float C::*member) {
  return {"steps-per-contact", member, "",
          kMinStepsPerContact, 1e4,    "substeps per Hertz contact time at the speed guard"};
}
template <class C>
Param<C> settleSpeedParam(float C::*member) {
  return {"settle-speed", member, "m/s", 0.0, 10.0, "the sand has settled below this rms speed"};
}
template <class C>
Param<C> maxSettleSecondsParam(float C::*member) {
  return {"max-settle-seconds", member, "s", 0.0, 1e6, "longest wait for the sand to settle"};
}

/// The shared rows of the members of `C` that have these names, in this order: friction,
/// youngsModulus, restitution, settleSpeed, maxSettleSeconds, stepsPerContact, seed and
/// particleDiameter. A member of one of these names is always that parameter.
template <class C>
std::vector<Param<C>> standardRows() {
  std::vector<Param<C>> rows;
  if constexpr (requires { &C::friction; }) rows.push_back(frictionParam(&C::friction));
  if constexpr (requires { &C::youngsModulus; }) {
    rows.push_back(youngsModulusParam(&C::youngsModulus));
  }
  if constexpr (requires { &C::restitution; }) rows.push_back(restitutionParam(&C::restitution));
  if constexpr (requires { &C::settleSpeed; }) rows.push_back(settleSpeedParam(&C::settleSpeed));
  if constexpr (requires { &C::maxSettleSeconds; }) {
    rows.push_back(maxSettleSecondsParam(&C::maxSettleSeconds));
  }
  if constexpr (requires { &C::stepsPerContact; }) {
    rows.push_back(stepsPerContactParam(&C::stepsPerContact));
  }
  if constexpr (requires { &C::seed; }) rows.push_back(seedParam(&C::seed));
  if constexpr (requires { &C::particleDiameter; }) {
    rows.push_back(diameterParam(&C::particleDiameter));
  }
  return rows;
}

/// A scene's own rows, then the standard rows of its Config that its own do not name (a scene
/// whose "friction" acts on the walls only says so in a row of its own).
template <class C>
std::vector<Param<C>> withStandardRows(std::span<const Param<C>> own) {
  std::vector<Param<C>> rows(own.begin(), own.end());
  for (const Param<C>& row : standardRows<C>()) {
    if (std::ranges::none_of(own, [&](const Param<C>& mine) { return mine.name == row.name; })) {
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace sandphys::scenes::kit
