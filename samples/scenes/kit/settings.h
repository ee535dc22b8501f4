#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include <sandphys/sandphys.h>

namespace sandphys::scenes::kit {

/// What a scene sets of its World's settings; the rest keeps WorldSettings' defaults.
struct SettingsRule {
  /// Capacities, exactly (reserveExactly): granules, other bodies and their particles.
  std::uint64_t granules = 0;
  std::uint64_t bodies = 0;
  std::uint64_t particles = 0;
  /// Speed guard, m/s.
  float maxSpeed = WorldSettings{}.maxSpeed;
  /// Substeps per Hertz contact time at the guard.
  float stepsPerContact = WorldSettings{}.stepsPerContact;
  /// Pa; 0 for sceneYoungsModulus's auto value.
  float youngsModulus = 0.0f;
  /// The grains' own, where the scene sets them.
  std::optional<float> friction;
  std::optional<float> restitution;
  /// Per-frame statistics, which the settle gates judge from.
  bool statsEachFrame = WorldSettings{}.statsEachFrame;
};

/// Sets `settings`' capacities to exactly `granules` granules plus `bodies` other bodies of
/// `particles` particles in all. Throws InvalidArgument naming `scene` and the counts when that
/// is more than a World can index.
void reserveExactly(WorldSettings& settings, std::string_view scene, std::uint64_t granules,
                    std::uint64_t bodies = 0, std::uint64_t particles = 0);

/// Mass of one granule of the World made from `settings`, kg.
float granuleMass(const WorldSettings& settings);

/// The settings of a World with particles of diameter `d` (m) under `rule`; the Young's modulus
/// is set last, as it follows from the diameter, the guard and the substeps. Throws
/// InvalidArgument naming `scene` when the capacities are more than a World can index.
WorldSettings worldSettings(std::string_view scene, float d, const SettingsRule& rule);

/// The lowest speed guard a scene sets, m/s: what its grains reach in settling drops.
inline constexpr float kMinGuardSpeed = 2.0f;
/// Substeps per Hertz contact time at the guard speed (SettingsRule::stepsPerContact) for scenes
/// whose guard is a worst case that few contacts reach: slower contacts last longer and get more
/// substeps, and 10 (the minimum is 8) halves the cost of the default 20.
inline constexpr float kGuardStepsPerContact = 10.0f;

/// Speed guard for a fall, or a frictionless slide, of `height` m under the default gravity, with
/// a margin for rebounds and the rim speed of spinning bodies; at least kMinGuardSpeed.
float fallGuardSpeed(float height);

/// Speed guard (WorldSettings::maxSpeed) for grains that leave an emitter at `speed` (m/s) and
/// fall `height` (m) under gravity `g` (m/s²): the impact with a margin for rebounds and the rim
/// speed of spinning grains, and at least kMinGuardSpeed.
float pourGuardSpeed(float speed, float height, float g);

/// Gravity of a World with default settings, m/s², for the scenes' speed guards.
inline const float kGravity = length(WorldSettings{}.gravity);

/// The Young's modulus (Pa) a scene's World gets for a configured `youngsModulus`: that value
/// when > 0; for 0 (auto) the one at which two granules meeting head-on at the scene's speed
/// guard overlap by kScenePeakOverlap (youngsModulusForPeakOverlap), so that no grain passes
/// through anything. The stiffer the sand, the shorter
/// the time step (t_n ∝ E^-2/5): a scene pays for its speed guard in substeps.
float sceneYoungsModulus(const WorldSettings& settings, float youngsModulus = 0.0f);
/// The closed-form peak overlap, in particle diameters, that an auto Young's modulus allows
/// (undamped: real impacts are slower than the guard and damped).
inline constexpr float kScenePeakOverlap = 0.3f;

}  // namespace sandphys::scenes::kit
