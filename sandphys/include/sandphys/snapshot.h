#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sandphys/math.h"

namespace sandphys {

/// One body slot exactly as the GPU stores it: the bits World::readStateHash covers.
struct StoredBody {
  std::array<float, 3> position{};  ///< centre of mass, m
  /// Orientation of the body's principal frame (ParticleTemplate::principalRotation), the frame
  /// the GPU integrates in: BodyState::orientation · principalRotation, kept as stored so that a
  /// restore is exact. The state hash and recordings take its words in the order x, y, z, w
  /// (docs/recording.md).
  Quat principalOrientation{};
  std::array<float, 3> velocity{};         ///< m/s
  std::array<float, 3> angularVelocity{};  ///< rad/s, world frame
  bool alive = true;                       ///< false once a sink removed it
  /// Calm count (WorldSettings::sleep, docs/architecture.md "sleep"): asleep at
  /// SleepModel::substeps; always 0 without sleep. Below 2^30.
  std::uint32_t calm = 0;
};

/// The one word the state hash and recordings keep of a StoredBody's alive flag and calm count:
/// bit 0 alive, the calm count above it (so 1 or 0 without sleep).
inline std::uint32_t statusWord(const StoredBody& b) {
  return (b.alive ? 1u : 0u) | (b.calm << 1);
}

/// The words the state hash and recordings keep of a StoredBody's principal orientation, in the
/// GPU's order: x, y, z, w.
inline std::array<float, 4> orientationWords(const StoredBody& b) {
  const Quat& q = b.principalOrientation;
  return {q.x, q.y, q.z, q.w};
}

/// Contact slots each particle owns under ContactLaw::HertzMindlin (docs/architecture.md,
/// "contacts"): contacts beyond these get no history and are counted.
inline constexpr std::uint32_t kContactSlots = 12;

/// One particle's contact history exactly as the GPU stores it (ContactLaw::HertzMindlin): each
/// slot's tangential spring (x, y, z as float bits) and partner key, the pair counts of its slots
/// (one byte per slot in pairs[0..2]) and the number of slots in use (pairs[3]). What a contact
/// carries from one substep to the next.
struct StoredContacts {
  std::array<std::array<std::uint32_t, 4>, kContactSlots> slots{};
  std::array<std::uint32_t, 4> pairs{};
};

/// One particle's rolling springs (Material::rollingFriction), slot by slot as its StoredContacts:
/// each slot's rolling displacement (x, y, z as float bits) exactly as the GPU stores it (whose
/// fourth word is always 0). What rolling friction carries from one substep to the next.
struct StoredRolling {
  std::array<std::array<std::uint32_t, 3>, kContactSlots> springs{};
};

/// One particle's contact force and torque from the last substep that computed them, exactly as
/// the GPU stores them (x, y, z as float bits, and the w words the kernels keep beside them). With
/// sleep a sleeping particle is not computed and these carry over from substep to substep: the
/// balance check of a sleeper that something awake touches sums them (docs/architecture.md,
/// "Sleep").
struct StoredForces {
  std::array<std::uint32_t, 4> force{};
  std::array<std::uint32_t, 4> torque{};
};

/// Every body slot in use at one moment (World::readSnapshot, a sync point).
struct WorldSnapshot {
  std::uint64_t frame = 0;     ///< frames run when it was taken (the caller's count; 0 = built)
  std::uint64_t steps = 0;     ///< World::stepCount
  double simulatedTime = 0.0;  ///< World::simulatedTime, s
  /// Frame time World::step had not yet run as a substep (its accumulator), s. Kept so that a
  /// World restored to a snapshot of its own takes its next frame as it would have; recordings
  /// do not store it (read back, it is 0).
  double unsteppedTime = 0.0;
  /// Substeps World::step held at its stopAt, not yet run (StepReport::substepsHeld); kept and
  /// not recorded like unsteppedTime.
  std::uint64_t heldSubsteps = 0;
  std::vector<StoredBody> bodies;
  /// Under ContactLaw::HertzMindlin, every particle slot in use; empty under PaperViscous (whose
  /// contacts keep nothing).
  std::vector<StoredContacts> contacts;
  /// With rolling friction (Material::rollingFriction > 0), every particle slot in use; empty
  /// without.
  std::vector<StoredRolling> rolling;
  /// With sleep (WorldSettings::sleep), every particle slot in use; empty without, where every
  /// substep computes every particle's force before it is used.
  std::vector<StoredForces> forces;
  /// The id (BodyId::index) of the body in each slot, once the sort of the granules by place
  /// (WorldSettings::sortInterval) has moved any; empty while every slot holds the body of its
  /// own index.
  std::vector<std::uint32_t> bodyIds;
};

/// The hash World::readStateHash computes on the GPU, computed here on the CPU from the same bits
/// (docs/recording.md gives the function). For tests and tools.
std::uint64_t stateHash(const WorldSnapshot& snapshot);

/// Where two states first differ: the lowest body slot, then the first field in the order of
/// StoredBody ("position.x" ... "principalOrientation.w" ... "angularVelocity.z", "alive",
/// "calm"); field "body count" when the
/// number of slots differs (body is then the smaller count). Then the contact history: the
/// lowest particle (subject Particle), "contact slot K spring.x" ... "contact slot K key",
/// "contact pairs W", or "particle count"; then the rolling springs: "contact slot K rolling.x"
/// ... "rolling.z", or "rolling count"; then the forces: "force.x" ... "torque.w", or "forces
/// count". Also for inputs (below).
struct StateDifference {
  enum class Subject { Body, Particle };
  std::uint32_t body = 0;  ///< body slot, or particle index when subject is Particle
  std::string field;
  double recorded = 0.0;
  double replayed = 0.0;
  Subject subject = Subject::Body;
  bool integer = false;  ///< the values are integers (keys, counts), not floats
  /// "body 17 velocity.y: recorded 0.123456791 (0x3dfcd6e9), replayed 0.123456798 (0x3dfcd6ea)";
  /// float fields with their bits.
  std::string describe() const;
};
std::optional<StateDifference> firstDifference(const WorldSnapshot& recorded,
                                               const WorldSnapshot& replayed);

}  // namespace sandphys
