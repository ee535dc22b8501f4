// The table of WorldSettings fields (sandphys/settings_fields.h).
#include "sandphys/settings_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/assert.h"
#include "core/validation.h"
#include "core/world_checks.h"

namespace sandphys {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using Kind = SettingField::Kind;

// Rows by kind, so that each line of the table reads as name, unit, range and meaning.
constexpr SettingField real(const char* member, const char* key, const char* label,
                            const char* unit, double min, bool minOpen, double max, bool maxOpen,
                            const char* help, float* (*at)(WorldSettings&)) {
  return {member, key, label, unit, Kind::Real, min, max, minOpen, maxOpen, help, at};
}
constexpr SettingField count(const char* member, const char* key, const char* label, double min,
                             double max, const char* help, std::uint32_t* (*at)(WorldSettings&)) {
  return {member, key, label, "", Kind::Count, min, max, false, false, help, nullptr, at};
}
constexpr SettingField flag(const char* member, const char* key, const char* label,
                            const char* help, bool* (*at)(WorldSettings&)) {
  return {member, key, label, "", Kind::Flag, 0, 1, false, false, help, nullptr, nullptr, at};
}

using W = WorldSettings;
const SettingField kFields[] = {
    real("particleDiameter", "particle_diameter", "particle diameter", "m", 0, true, kInf, false,
         "d of every particle; the neighbour grid's cells are d + listSkin",
         [](W& s) { return &s.particleDiameter; }),
    real("gravity.x", "gravity_x", "gravity x", "m/s^2", -kInf, true, kInf, true,
         "gravitational acceleration, x", [](W& s) { return &s.gravity.x; }),
    real("gravity.y", "gravity_y", "gravity y", "m/s^2", -kInf, true, kInf, true,
         "gravitational acceleration, y (up)", [](W& s) { return &s.gravity.y; }),
    real("gravity.z", "gravity_z", "gravity z", "m/s^2", -kInf, true, kInf, true,
         "gravitational acceleration, z", [](W& s) { return &s.gravity.z; }),
    real("material.density", "density", "density", "kg/m^3", 0, true, kInf, false,
         "of the grain material; a particle's mass is density pi d^3 / 6",
         [](W& s) { return &s.material.density; }),
    real("material.youngsModulus", "youngs_modulus", "Young's modulus", "Pa", 0, true, kInf, false,
         "stiffer sand needs a smaller time step: dt ~ E^(-2/5)",
         [](W& s) { return &s.material.youngsModulus; }),
    real("material.poissonRatio", "poisson_ratio", "Poisson's ratio", "", 0, false, 0.5, true,
         "enters the effective normal and shear moduli",
         [](W& s) { return &s.material.poissonRatio; }),
    real("material.restitution", "restitution", "restitution", "", 0, true, 1, false,
         "normal coefficient of restitution of a grain-grain impact",
         [](W& s) { return &s.material.restitution; }),
    real("material.friction", "friction", "friction", "", 0, false, kInf, false,
         "Coulomb coefficient between grains: a contact sticks below mu F_n",
         [](W& s) { return &s.material.friction; }),
    real("material.rollingFriction", "rolling_friction", "rolling friction", "", 0, false, kInf,
         false, "a contact resists relative rolling with a torque mu_r R F_n (0: none)",
         [](W& s) { return &s.material.rollingFriction; }),
    real("material.tangentialDamping", "tangential_damping", "tangential damping", "N s/m", 0,
         false, kInf, false, "the paper's law only; 0: a quarter of the stability limit",
         [](W& s) { return &s.material.tangentialDamping; }),
    {"contactLaw", "contact_law", "contact law", "", Kind::Law, 0, 1, false, false,
     "ContactLaw::HertzMindlin (0) or ContactLaw::PaperViscous (1)", nullptr, nullptr, nullptr,
     [](W& s) { return &s.contactLaw; }},
    real("timeStep", "time_step", "time step", "s", 0, false, kInf, false,
         "fixed substep; 0 derives it from the contact time and stepsPerContact",
         [](W& s) { return &s.timeStep; }),
    real("stepsPerContact", "steps_per_contact", "steps per contact", "", kMinStepsPerContact,
         false, kMaxStepsPerContact, false,
         "substeps per Hertz contact time when the step is derived",
         [](W& s) { return &s.stepsPerContact; }),
    real("maxSpeed", "max_speed", "speed guard", "m/s", 0, true, kInf, false,
         "faster bodies are clamped; the impact speed of the stiffness check",
         [](W& s) { return &s.maxSpeed; }),
    real("listSkin", "list_skin", "list skin", "m", 0, false, kInf, false,
         "neighbour lists reach d + skin; 0 derives it from maxSpeed (at most d)",
         [](W& s) { return &s.listSkin; }),
    count("sortInterval", "sort_interval", "sort interval", 0, kNeverSortGranules,
          "substeps between sorts of the granules by place (with sleep, of those computed); 0 "
          "derives it (1000); the largest value: never",
          [](W& s) { return &s.sortInterval; }),
    count("maxSubstepsPerFrame", "max_substeps_per_frame", "substeps per frame, at most", 1, kInf,
          "time beyond it is dropped and reported", [](W& s) { return &s.maxSubstepsPerFrame; }),
    count("maxBodies", "max_bodies", "body capacity", 1, kInf, "grown only by World::reserve",
          [](W& s) { return &s.maxBodies; }),
    count("maxParticles", "max_particles", "particle capacity", 0, kMaxParticleCapacity,
          "0: 4 maxBodies (every body a granule)", [](W& s) { return &s.maxParticles; }),
    count("maxColliders", "max_colliders", "collider capacity", 1, kMaxColliderCapacity,
          "of implicit colliders and of sinks, each", [](W& s) { return &s.maxColliders; }),
    flag("statsEachFrame", "stats_each_frame", "stats each frame",
         "one small read-back per World::step fills StepReport::stats",
         [](W& s) { return &s.statsEachFrame; }),
    flag(
        "profileKernels", "profile_kernels", "profile kernels",
        "GL timer queries around every kernel (World::kernelTimes); on llvmpipe they slow the step",
        [](W& s) { return &s.profileKernels; }),
    flag("sleep.enabled", "sleep", "sleeping sand",
         "granules at rest fall asleep and cost less until something touches them",
         [](W& s) { return &s.sleep.enabled; }),
    real("sleep.linearSpeed", "sleep_linear_speed", "sleep speed", "m/s", 0, false, kInf, false,
         "0: kSleepLinearSpeed sqrt(g d)", [](W& s) { return &s.sleep.linearSpeed; }),
    real("sleep.angularSpeed", "sleep_angular_speed", "sleep spin", "rad/s", 0, false, kInf, false,
         "0: kSleepAngularSpeed sqrt(g / d)", [](W& s) { return &s.sleep.angularSpeed; }),
    real("sleep.time", "sleep_time", "sleep time", "s", 0, false, kInf, false,
         "calm this long before sleep; 0: kSleepTime sqrt(d / g)",
         [](W& s) { return &s.sleep.time; }),
    real("sleep.wakeAcceleration", "sleep_wake_acceleration", "wake acceleration", "m/s^2", 0,
         false, kInf, false, "unbalanced force per mass that wakes; 0: kSleepWakeAcceleration g",
         [](W& s) { return &s.sleep.wakeAcceleration; }),
};

}  // namespace

double SettingField::valueIn(const WorldSettings& settings) const {
  auto& s = const_cast<WorldSettings&>(settings);  // the accessors only read here
  switch (kind) {
    case Kind::Real:
      return *real(s);
    case Kind::Count:
      return *count(s);
    case Kind::Flag:
      return *flag(s) ? 1.0 : 0.0;
    case Kind::Law:
      return double(unsigned(*law(s)));
  }
  SANDPHYS_ASSERT(false, "SettingField kind " + std::to_string(int(kind)) + " of " + member);
}

bool SettingField::accepts(double value) const {
  if (kind == Kind::Real && !std::isfinite(value)) return false;
  const bool aboveMin = minOpen ? value > min : value >= min;
  const bool belowMax = maxOpen ? value < max : value <= max;
  return aboveMin && belowMax;
}

std::string SettingField::rangeText() const {
  using detail::formatValue;
  if (kind == Kind::Law) return std::string("must be ") + help;  // the enumerators, by name
  std::string text;
  if (std::isinf(min) && std::isinf(max)) {
    text = "must be finite";
  } else if (kind == Kind::Count && min <= 0.0) {
    text = "must be <= " + formatValue(max);  // no count is below 0
  } else if (std::isinf(max)) {
    text = std::string(kind == Kind::Real ? "must be finite and " : "must be ") +
           (minOpen ? "> " : ">= ") + formatValue(min);
  } else {
    text = "must be in " + std::string(minOpen ? "(" : "[") + formatValue(min) + ", " +
           formatValue(max) + (maxOpen ? ")" : "]");
  }
  if (*unit) text += std::string(" (") + unit + ")";
  return text;
}

std::span<const SettingField> worldSettingFields() {
  return kFields;
}

const SettingField* findWorldSettingField(std::string_view key) {
  const auto it = std::find_if(std::begin(kFields), std::end(kFields),
                               [&](const SettingField& f) { return key == f.key; });
  return it == std::end(kFields) ? nullptr : &*it;
}

namespace detail {

void checkSettingRanges(const WorldSettings& settings) {
  for (const SettingField& field : kFields) {
    const double value = field.valueIn(settings);
    require(field.accepts(value), std::string("WorldSettings.") + field.member, value,
            field.rangeText());
  }
}

}  // namespace detail
}  // namespace sandphys
