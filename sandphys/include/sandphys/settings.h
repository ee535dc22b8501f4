#pragma once

#include <cstdint>

#include "sandphys/math.h"

namespace sandphys {

/// How particles of different bodies (and particles and colliders) push on each other
/// (docs/architecture.md, "contacts"). Fixed at World creation.
enum class ContactLaw : unsigned {
  /// What LAMMPS `pair granular` (hertz/material, damping tsuji, tangential mindlin) and
  /// LIGGGHTS do: Hertz normal force with Tsuji damping; a Mindlin tangential spring with history
  /// (k_t = 8 G* a), Coulomb-capped, kept per contact across substeps; both forces act at the
  /// contact point, so friction turns bodies; damping from the masses of the two bodies. No force
  /// cap: settings whose peak overlap could let grains pass through each other are refused.
  HertzMindlin = 0,
  /// The law of Longmore et al. 2013 as published (eq. 9, 10): friction min(μ F_n, γ_s |v_s|)
  /// with no memory, applied at particle centres, damping from particle masses and the overlap
  /// capped at d/10. For rerunning the paper's experiments; loaded sand creeps under it.
  PaperViscous = 1,
};

/// Bulk material of the sand grains. Validated when a World is created.
struct Material {
  /// Density of the grain material in kg/m³; > 0. Sets particle mass = density · πd³/6.
  float density = 2600.0f;
  /// Young's modulus E in Pa; > 0. Sets the Hertz stiffness (and so the time step, t_n ∝ E^-2/5).
  /// Under ContactLaw::HertzMindlin a World refuses an E so low that a grain meeting another
  /// grain or a wall at WorldSettings::maxSpeed would overlap it far enough to pass through.
  float youngsModulus = 1.0e7f;
  /// Poisson's ratio ν; in [0, 0.5). Enters the effective moduli E* = E / (2 (1 - ν²)) and,
  /// for the tangential spring, G* = E / (4 (2 - ν)(1 + ν)).
  float poissonRatio = 0.3f;
  /// Normal coefficient of restitution of a grain-grain impact; in (0, 1]. Sets the normal damping.
  float restitution = 0.5f;
  /// Coulomb friction coefficient μ between grains; >= 0. A contact sticks while its tangential
  /// force is below μ F_n.
  float friction = 0.5f;
  /// ContactLaw::HertzMindlin only: coefficient of rolling friction μ_r, dimensionless; >= 0 (0:
  /// none, as in LAMMPS and LIGGGHTS by default). Each contact of a grain, with a grain or a
  /// collider, resists the relative rolling of its two bodies with a rolling spring, damper and
  /// slider as LAMMPS's `rolling sds`: a couple of at most μ_r R F_n (R the effective rolling
  /// radius: d/4 between two particles, d/2 against a collider), which holds a loaded contact
  /// still below that limit (a sphere rests on a slope of tan θ < μ_r). Without it a granule
  /// resting on two contacts can rock about the line through them for ever. Costs 192 B per
  /// particle for the rolling springs (docs/architecture.md, "contacts").
  float rollingFriction = 0.0f;
  /// ContactLaw::PaperViscous only: tangential damping γs of eq. 10 in N·s/m; >= 0. 0 selects
  /// the automatic value 0.25 · particle mass / time step (a quarter of the explicit stability
  /// limit). HertzMindlin derives its tangential damping from the restitution.
  float tangentialDamping = 0.0f;
};

/// Friction and restitution of an implicit collider (its stiffness follows the sand's Material,
/// with the collider treated as rigid).
struct SurfaceMaterial {
  /// Coulomb friction coefficient μ against grains; >= 0.
  float friction = 0.5f;
  /// Normal coefficient of restitution of a grain hitting this surface; in (0, 1].
  float restitution = 0.5f;
};

/// When granules fall asleep and wake (docs/architecture.md, "sleep"). A granule whose speeds
/// stay below both thresholds for `time` falls asleep if every granule it touches has been calm
/// as long (counted along the contacts, so that a touching group falls asleep together); asleep,
/// it is not integrated and its contacts with sleeping or immovable partners are not computed.
/// It wakes when a touching body moves, when its contacts change, when the force on it departs
/// from what held it at rest by more than wakeAcceleration (per unit mass), and on World::wake.
/// Zero fields take the defaults from d and g = |gravity|. ContactLaw::HertzMindlin only.
struct SleepSettings {
  /// Off keeps every granule awake, and the step exactly as without sleep. Without rolling
  /// friction a settled pile keeps a few granules rocking on two contacts, and each holds a band
  /// of neighbours awake; with Material::rollingFriction > 0 it sleeps whole (bench/README.md,
  /// "Rolling friction and the granules that never sleep").
  bool enabled = false;
  /// Linear speed threshold in m/s; >= 0. 0 selects kSleepLinearSpeed · sqrt(g d).
  float linearSpeed = 0.0f;
  /// Angular speed threshold in rad/s; >= 0. 0 selects kSleepAngularSpeed · sqrt(g / d).
  float angularSpeed = 0.0f;
  /// Time below both thresholds before sleep, in s; >= 0. 0 selects kSleepTime · sqrt(d / g).
  float time = 0.0f;
  /// Unbalanced force per unit mass (m/s²) that wakes a sleeping granule touched by an awake
  /// one; >= 0. 0 selects kSleepWakeAcceleration · g.
  float wakeAcceleration = 0.0f;
};

/// The defaults of SleepSettings, in units of sqrt(g d), sqrt(g / d), sqrt(d / g) and g.
inline constexpr float kSleepLinearSpeed = 0.01f;
inline constexpr float kSleepAngularSpeed = 0.02f;
inline constexpr float kSleepTime = 10.0f;
inline constexpr float kSleepWakeAcceleration = 0.5f;
/// How far, in contacts, the calm of a granule waits for its neighbours' (docs/architecture.md,
/// "sleep"): a granule sleeps only when nothing within this many contacts of it still moves.
inline constexpr std::uint32_t kSleepContacts = 4;

/// Everything a World needs at creation. Plain aggregate: designated initialisers work on it.
struct WorldSettings {
  /// Diameter d of every particle in m; > 0. The neighbour grid's cells are d + listSkin.
  float particleDiameter = 0.02f;
  /// Gravitational acceleration in m/s².
  Vec3 gravity{0.0f, -9.81f, 0.0f};
  /// Grain material.
  Material material{};
  /// The contact law (see ContactLaw).
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
  /// Fixed substep in s. 0 derives it: t_n(maxSpeed) / stepsPerContact (eq. 11, Hertz form).
  /// A value above t_n / kMinStepsPerContact or below t_n / kMaxStepsPerContact is refused.
  float timeStep = 0.0f;
  /// Substeps per Hertz contact duration when the step is derived; in [kMinStepsPerContact,
  /// kMaxStepsPerContact].
  float stepsPerContact = 20.0f;
  /// Speed guard in m/s; > 0. Body speeds above it are clamped (and counted); it is also the
  /// impact speed at which the contact duration t_n that sets the time step, and the peak
  /// overlap that HertzMindlin checks, are evaluated. 4 m/s is a fall of 0.8 m.
  float maxSpeed = 4.0f;
  /// Skin of the neighbour lists in m: a particle lists the particles closer than d + skin, and
  /// the lists are built again once some particle has moved half the skin. 0 derives it
  /// (ContactModel::listSkin: room for kListSkinSubsteps substeps at maxSpeed, within
  /// [kMinListSkin, kMaxListSkin] · d); otherwise in (0, d]. Contacts are summed in partner order
  /// whenever the lists were built, so it changes no bit of the result until the first sort of
  /// the granules (sortInterval), whose order follows the grid's cells of d + skin.
  float listSkin = 0.0f;
  /// Substeps between sorts of the granules by place. Sand that flows or is poured ends up with
  /// neighbours far apart in memory, which costs every contact pass; LAMMPS sorts its atoms every
  /// 1000 steps for the same reason. A sort moves the states of the free, living granules among
  /// their slots so that slot order follows a walk through the grid; BodyIds stay the bodies' own.
  /// The sum over a particle's contacts then runs in another order, so the bits of the result
  /// depend on it (deterministically). With sleep only the granules a substep computes are
  /// sorted, among their own slots, and a substep that computes nothing sorts nothing. 0 derives
  /// it: kSortInterval; kNeverSortGranules: never.
  std::uint32_t sortInterval = 0;
  /// Substeps one call of World::step may run; > 0. Time beyond it is dropped and reported.
  std::uint32_t maxSubstepsPerFrame = 512;
  /// Capacity of bodies (granules, sampled bodies, rough floors); fixed at creation, grown only
  /// by World::reserve. > 0.
  std::uint32_t maxBodies = 65536;
  /// Capacity of particles; 0 means 4 · maxBodies (every body a granule).
  std::uint32_t maxParticles = 0;
  /// Capacity of implicit colliders and of sinks (each).
  std::uint32_t maxColliders = 64;
  /// Reduce and read the small statistics buffer after each World::step (one sync per frame,
  /// never per substep). Off: StepReport carries only CPU-side numbers; use World::readStats.
  /// Either way, with sleep, frames of sleeping sand are found and skipped (off, from a copy of
  /// a few counters that the next frame takes if the GPU has made it, never waiting).
  bool statsEachFrame = true;
  /// Record GL timer queries per kernel (costs a little; read with World::kernelTimes).
  bool profileKernels = false;
  /// Sleeping sand (off by default).
  SleepSettings sleep{};
};

/// Most particles a World may hold (WorldSettings::maxParticles, World::reserve): more would
/// exceed the 128 MiB a single GL storage buffer may hold on Mesa (64 bytes per particle in each
/// group of contact slots).
inline constexpr std::uint32_t kMaxParticleCapacity = 1u << 21;

/// Most implicit colliders (and sinks) a World may hold (WorldSettings::maxColliders): collider
/// keys of the contact slots hold the collider and its face in 23 bits, and every contact loops
/// over the colliders, so far fewer are practical.
inline constexpr std::uint32_t kMaxColliderCapacity = 1u << 16;

/// Fewest substeps per contact duration t_n a World accepts; fewer is refused as unstable.
inline constexpr float kMinStepsPerContact = 8.0f;
/// Most substeps per contact duration t_n a World accepts. A contact is resolved long before
/// that; a finer step only multiplies the cost (and, far enough, moves a grain at rest by less
/// than a float can tell).
inline constexpr float kMaxStepsPerContact = 1.0e4f;

/// Coarsest float spacing, in particle diameters, a World accepts where it places a body: a body
/// (or block, floor, emitter) reaching farther than kMaxPositionSpacing · d · 2^23 from the origin
/// (about 84,000 d) is refused, since contacts there would be resolved in steps coarser than their
/// overlaps.
inline constexpr float kMaxPositionSpacing = 0.01f;

/// Substeps between sorts of the granules by place when WorldSettings::sortInterval is 0:
/// LAMMPS's default (`atom_modify sort 1000`).
inline constexpr std::uint32_t kSortInterval = 1000;
/// WorldSettings::sortInterval of a World that never sorts its granules: the largest value the
/// field takes.
inline constexpr std::uint32_t kNeverSortGranules = 1u << 30;

/// Substeps between sorts of the granules by place in a World of `settings`
/// (WorldSettings::sortInterval, derived); 0: never.
inline std::uint32_t granuleSortInterval(const WorldSettings& settings) {
  if (settings.sortInterval == kNeverSortGranules) return 0;
  if (settings.sortInterval > 0) return settings.sortInterval;
  return kSortInterval;
}

/// The derived skin of the neighbour lists (WorldSettings::listSkin = 0): 2 · kListSkinSubsteps ·
/// maxSpeed · timeStep, so that a particle at the speed guard keeps its list that many substeps,
/// clamped to [kMinListSkin, kMaxListSkin] particle diameters.
inline constexpr float kListSkinSubsteps = 10.0f;
inline constexpr float kMinListSkin = 0.05f;
inline constexpr float kMaxListSkin = 0.5f;
/// The near skin of the lists (ContactModel::listNearSkin), as a fraction of the skin. Without
/// sleep the contacts passes test only the entries of a list that were within d + near skin
/// when it was last marked, and it is marked again once some particle has moved half the near
/// skin: a cheaper scan in a resting pile, for a marking that costs about one scan.
inline constexpr float kListNearSkinFraction = 0.25f;

}  // namespace sandphys
