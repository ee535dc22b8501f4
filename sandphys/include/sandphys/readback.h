#pragma once

#include <cstdint>

#include "sandphys/body.h"
#include "sandphys/ids.h"
#include "sandphys/math.h"

namespace sandphys {

/// One body as read back from the GPU (World::readBodies, a sync point).
struct BodyState {
  BodyId id;                        ///< the body, as addBody or addGranules returned it
  Vec3 position{};                  ///< centre of mass, m
  Quat orientation{};               ///< orientation of the template's original frame
  Vec3 velocity{};                  ///< m/s
  Vec3 angularVelocity{};           ///< rad/s, world frame
  bool alive = true;                ///< false once a sink removed it
  bool granule = true;              ///< a sand granule (not a floor or sampled body)
  Motion motion = Motion::Dynamic;  ///< as added: a rough floor is Static
};

/// One particle as read back from the GPU (World::readParticles, a sync point). Position and
/// velocity are the state the next substep starts from (its body's, now); the force is the one
/// the last substep computed, from the state before it.
struct ParticleState {
  BodyId body;      ///< the body the particle belongs to
  Vec3 position{};  ///< m
  Vec3 velocity{};  ///< m/s
  Vec3 force{};     ///< contact + collider force of the last substep, N (no gravity)
};

/// One contact as read back from the GPU (World::readContacts, a sync point): the contacts the
/// next substep applies, at the state it starts from (ParticleState), with the tangential springs
/// advanced as it advances them. Particle-particle contacts appear once (from the side that keeps
/// history: particleA < particleB, or the movable one against a static particle); collider
/// contacts have particleB = kNone, an invalid bodyB and the collider's id.
struct ContactRecord {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  /// Particles by their position in World::readParticles (plain indices: particles have no ids).
  std::uint32_t particleA = 0;
  std::uint32_t particleB = kNone;
  BodyId bodyA;              ///< particleA's body
  BodyId bodyB;              ///< particleB's body; invalid for a collider contact
  ColliderId collider;       ///< the collider of a collider contact; invalid for two particles
  Vec3 point{};              ///< midpoint of the overlap, m
  Vec3 normal{};             ///< unit, from B (or the collider) towards A
  float normalForce = 0.0f;  ///< F_n on A, N (>= 0)
  Vec3 tangentialForce{};    ///< F_s on A, N
  float overlap = 0.0f;      ///< ξ, m
  /// ContactLaw::HertzMindlin: A's tangential spring displacement δ after that substep, m (in
  /// the tangent plane; its length times k_t is the stick force). Zero under PaperViscous.
  Vec3 tangentialDisplacement{};
  /// Rolling friction (Material::rollingFriction): its couple on A's body, N m, and A's rolling
  /// spring displacement δ_r after that substep, m (docs/architecture.md, "contacts"). Zero
  /// without rolling friction.
  Vec3 rollingTorque{};
  Vec3 rollingDisplacement{};
};

/// The sand's push on one body that is not a granule (a sampled mesh, a body coupled to another
/// engine, a tool): contact forces from granules and colliders, summed on the GPU over the
/// substeps since the previous World::takeBodyForces that computed the body. Gravity is not
/// included.
struct BodyForce {
  BodyId body;
  Vec3 force{};   ///< sum over the substeps of the contact force, N
  Vec3 torque{};  ///< sum over the substeps of the torque about the centre of mass, N m
  /// Substeps summed: those that computed the body. With WorldSettings::sleep a sleeping body is
  /// computed only while something awake touches it, so this is 0 while it sleeps untouched (the
  /// force on it is then the last one computed).
  std::uint32_t substeps = 0;
  /// Mean force and torque over those substeps (zero when there were none).
  Vec3 meanForce() const;
  Vec3 meanTorque() const;
};

/// Totals over the world, reduced on the GPU (World::readStats, a sync point).
struct WorldStats {
  std::uint32_t bodies = 0;     ///< body slots in use (alive or not)
  std::uint32_t particles = 0;  ///< particle slots in use
  std::uint32_t granulesSpawned = 0;
  std::uint32_t granulesAlive = 0;
  /// Of them, asleep (WorldSettings::sleep); the others are awake.
  std::uint32_t granulesAsleep = 0;
  std::uint32_t granulesKilled = 0;  ///< removed by sinks
  /// Emitted granules that were not born because their place was taken (a grain thrown back up
  /// under an emitter); they never move nor touch anything.
  std::uint32_t granulesNotBorn = 0;
  /// Particle-particle pairs + collider contacts, last substep (a sleeping particle's: its last
  /// computed one; after restoreSnapshot, under HertzMindlin, those its contact history holds).
  std::uint32_t contacts = 0;
  /// Buckets of the neighbour grid's hash table that a list build scans: a power of two of at
  /// least 4096 that follows the particles in use, not the capacity reserved.
  std::uint32_t gridBuckets = 0;
  /// Builds of the neighbour lists so far (total): on the GPU's decision, when a particle has
  /// moved half the skin (WorldSettings::listSkin), a granule died or bodies were added.
  std::uint64_t listBuilds = 0;
  /// Markings of the lists' near part so far (total; 0 with WorldSettings::sleep): after each
  /// build, and when a particle has moved half the near skin (ContactModel::listNearSkin).
  std::uint64_t listNearMarkings = 0;
  /// Particles that had more partners within d + skin than a neighbour list holds at a build
  /// (total over builds). Their further partners are found in the grid each substep: exact, only
  /// slower.
  std::uint64_t neighbourListOverflows = 0;
  /// Sorts of the granules by place so far (total; WorldSettings::sortInterval, 0 without): one
  /// in each substep that the World's earlier substeps number a multiple of the interval (with
  /// 1000: the 1001st, the 2001st, ...). With sleep, such a substep that computes nothing moves
  /// nothing, and counts.
  std::uint64_t granuleSorts = 0;
  /// WorldSettings::sleep (0 without): the builds that sorted the sleepers into a grid again
  /// (total: the CPU changed the bodies, or enough sleepers had moved since), and the particles
  /// the last build sorted into its moving grid, the awake ones and the sleepers that moved
  /// since; the other sleepers stay sorted from before (docs/architecture.md, "Sleep").
  std::uint64_t stillGridBuilds = 0;
  std::uint32_t movingGridParticles = 0;
  double kineticEnergy = 0.0;  ///< translational + rotational of dynamic bodies, J
  double maxOverlap = 0.0;     ///< largest overlap since the last step() or resetPeakOverlap(), m
  /// ContactLaw::PaperViscous: contacts whose overlap exceeded d/10 and was capped (total).
  std::uint64_t penetrationClamps = 0;
  /// ContactLaw::HertzMindlin: contacts that found all of their particle's kContactSlots slots
  /// taken and acted without history that substep (total; should stay 0).
  std::uint64_t contactSlotOverflows = 0;
  std::uint64_t velocityClamps = 0;  ///< bodies slowed to maxSpeed (total)
  std::uint64_t steps = 0;           ///< substeps run in total
  double simulatedTime = 0.0;        ///< s
};

}  // namespace sandphys
