#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

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
template <class C>
Param<C> youngsModulusParam(float C::*member) {
  return {"youngs-modulus",
          member,
          "Pa",
          0.0,
          1e12,
          "Young's modulus of the grains (0: auto, stiff enough that two grains "
          "meeting at the scene's speed guard overlap by 0.3 d)"};
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

}  // namespace sandphys::scenes::kit
