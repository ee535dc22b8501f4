#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sandphys/body.h"
#include "sandphys/colliders.h"
#include "sandphys/contact_model.h"
#include "sandphys/gpu_context.h"
#include "sandphys/ids.h"
#include "sandphys/kinematic_move.h"
#include "sandphys/readback.h"
#include "sandphys/settings.h"
#include "sandphys/sleep_model.h"
#include "sandphys/snapshot.h"
#include "sandphys/spawn.h"
#include "sandphys/step_report.h"

namespace sandphys {

namespace detail {
struct WorldAccess;
}

/// GPU time of one kernel, summed over the substeps of the last World::step (profileKernels).
struct KernelTime {
  std::string name;
  double milliseconds = 0.0;
  std::uint32_t dispatches = 0;
};

/// GPU memory of one of a World's buffers (World::gpuMemoryByBuffer).
struct BufferMemory {
  std::string name;  ///< the buffer's array name in the kernels, or "params" (the uniform block)
  std::uint64_t bytes = 0;
};

/// A simulation of sand granules and particle-sampled bodies, entirely on the GPU.
///
/// Capacities are fixed at creation (WorldSettings) and grown only by reserve(); nothing is
/// allocated inside step(). Setup calls throw sandphys::Error; step() does not throw. Calls that
/// read GPU memory are marked "sync point": they wait for the GPU and are meant for analysis,
/// tests and debugging, not for every frame of a game. Two worlds may share one GpuContext. A
/// World that was moved from holds nothing: every call on it but destruction and assignment
/// throws InvalidArgument (step() included).
class World {
 public:
  /// Validates `settings` (throws InvalidArgument naming field, value and limit), compiles the
  /// kernels (GpuError with file and line on failure) and allocates every buffer.
  World(const GpuContext& gpu, const WorldSettings& settings);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Every check the constructor makes of `settings`, without a GPU: throws InvalidArgument
  /// naming the field, value and limit (a tool can vet settings before it creates a World).
  static void checkSettings(const WorldSettings& settings);

  const WorldSettings& settings() const;
  /// The resolved contact law (stiffness, damping, time step).
  const ContactModel& contactModel() const;
  /// The resolved sleep settings (thresholds, substeps before sleep).
  const SleepModel& sleepModel() const;
  /// The fixed substep, s.
  float timeStep() const;

  // --- Scene setup --------------------------------------------------------------------------
  ColliderId addCollider(const Plane& plane);
  ColliderId addCollider(const Box& box);
  ColliderId addCollider(const Cylinder& cylinder);
  ColliderId addCollider(const Funnel& funnel);
  /// Moves or reshapes an existing collider (same kind or another) at once; its surface moves
  /// as the descriptor's `motion` says. Throws InvalidId.
  void setCollider(ColliderId id, const Plane& plane);
  void setCollider(ColliderId id, const Box& box);
  void setCollider(ColliderId id, const Cylinder& cylinder);
  void setCollider(ColliderId id, const Funnel& funnel);
  /// Like setCollider, with `motion` derived from the change of pose since the collider was last
  /// given, over `seconds` (> 0; typically the frame about to be stepped): the reference point's
  /// displacement / seconds, and for a box the rotation angle / seconds about its axis. A
  /// descriptor of another kind than before gets zero motion. Throws InvalidId, InvalidArgument.
  void moveCollider(ColliderId id, const ColliderShape& shape, float seconds);
  /// A kill volume; removed granules are counted in WorldStats::granulesKilled. Wakes the
  /// granules in it.
  SinkId addSink(const Sink& sink);
  /// Wakes every sleeping granule whose centre lies in the box [lo, hi] (docs/architecture.md,
  /// "sleep"); the granules it touches wake too if it then moves. Nothing without sleep. Throws
  /// InvalidArgument for non-finite or inverted bounds.
  void wake(Vec3 lo, Vec3 hi);
  /// A static particle floor (see RoughFloor); returns its body.
  BodyId addRoughFloor(const RoughFloor& floor);
  /// Adds one rigid body built from `shape`; throws CapacityExceeded when bodies or particles run
  /// out (nothing is added then).
  BodyId addBody(const ParticleTemplate& shape, const BodyDesc& desc);
  /// Adds a block of tetrahedral granules; all or nothing (CapacityExceeded names the limit).
  /// Returns their ids.
  BodyRange addGranules(const GranuleBlock& block);
  /// Adds one tetrahedral granule at each pose (orientation of the granule template, as
  /// readBodies gives it back), in one upload; all or nothing. Every desc must be
  /// Motion::Dynamic with finite fields (InvalidArgument names the index and field).
  std::vector<BodyId> addGranules(std::span<const BodyDesc> granules);
  /// Adds an emitter; it runs inside step().
  EmitterId addEmitter(const EmitterSettings& emitter);
  void removeEmitter(EmitterId id);
  /// Sets the pose and velocities of a body (typically a kinematic one) before the next step.
  /// While a move of the body runs (moveKinematic), the move sets them again at the next substep.
  void setBodyState(BodyId id, const BodyDesc& state);
  /// Makes kinematic body `id` follow `move` (KinematicMove: from which substep to which, and
  /// its pose and velocity at each), in place of any move it had; returns those substeps, so
  /// that a scene can stop a step where the move starts or ends (step(frameDt, stopAt)). The
  /// World places the body after every substep the move covers (a 64-byte upload each; nothing
  /// when no move runs), so the path does not depend on how frames divide the substeps, and a
  /// World restored to a snapshot (restoreSnapshot) runs it from there as it ran before: a move
  /// is the World's setup, like a collider, not part of the snapshot. Throws InvalidId for a
  /// stale id; InvalidArgument naming the field and value for a body that is not kinematic, a
  /// non-finite or unresolvable position, a zero orientation, a negative or non-finite duration
  /// or a start before the World's current substep.
  KinematicMovePlan moveKinematic(BodyId id, const KinematicMove& move);
  /// Puts every body slot the snapshot holds back to its stored state, bit for bit, with the
  /// step count, simulated time and unstepped frame time; slots added after it (bodies an emitter
  /// or a scene added later) are marked not alive, so they neither move nor touch anything nor
  /// show. The World's bodies, colliders and emitters are otherwise as they are: a World that
  /// reached the snapshot's frame the same way continues from it exactly as it did then. Throws
  /// InvalidArgument when the snapshot holds more slots than the World has (nothing is changed
  /// then).
  void restoreSnapshot(const WorldSnapshot& snapshot);
  /// Grows the capacities to at least these counts (copies the buffers on the GPU). The only call
  /// that reallocates; never called by step().
  void reserve(std::uint32_t maxBodies, std::uint32_t maxParticles);

  // --- Simulation --------------------------------------------------------------------------
  /// Advances by `frameDt` seconds in whole fixed substeps: an accumulator carries the remainder
  /// to the next call; at most maxSubstepsPerFrame run and the rest is dropped (reported, and a
  /// warning is logged once, setLogHandler). Does not throw; non-finite or negative frameDt runs
  /// nothing. With sleep, a frame whose first substep finds all the sand asleep and untouched
  /// runs no GPU work for the others, which would change no bit (StepReport::idleSubsteps).
  StepReport step(float frameDt);
  /// Like step(frameDt), but stops when stepCount() reaches `stopAt`, e.g. to read a body's force
  /// exactly where a move starts (moveKinematic): the frame's substeps due beyond it are held
  /// (StepReport::substepsHeld), and the next call runs them before those of its own frameDt,
  /// within one cap; step(0.0f, stopAt) runs only them. stopAt <= stepCount() runs nothing and
  /// holds every substep due. StepReport::append joins the parts' reports into the frame's.
  StepReport step(float frameDt, std::uint64_t stopAt);
  /// Runs exactly `count` substeps, bypassing the accumulator (tests, single stepping), every one
  /// on the GPU (no idle substep is skipped).
  void substep(std::uint32_t count = 1);

  // --- Counts (CPU side, no sync) ----------------------------------------------------------
  std::uint32_t bodyCount() const;
  std::uint32_t particleCount() const;
  std::uint32_t granulesSpawned() const;
  std::uint32_t bodyCapacity() const;
  std::uint32_t particleCapacity() const;
  std::uint64_t stepCount() const;
  double simulatedTime() const;
  /// Bytes of GPU memory held by this world's buffers.
  std::uint64_t gpuMemoryBytes() const;
  /// The same bytes buffer by buffer, in the order of the library's buffer table (the uniform
  /// block last; buffers a World does not use hold their smallest size). They add up to
  /// gpuMemoryBytes(). No sync.
  std::vector<BufferMemory> gpuMemoryByBuffer() const;
  /// Every collider as last given to addCollider/setCollider, indexed by ColliderId::index (for
  /// renderers and debug drawing). A copy of CPU-side descriptors; no sync.
  std::vector<ColliderShape> colliders() const;

  // --- Read-back (every one is a sync point) ------------------------------------------------
  /// One state per body, in id order (readBodies()[id.index] is body `id`), each with its typed
  /// id.
  std::vector<BodyState> readBodies() const;
  /// Throws InvalidId for an invalid or stale id.
  BodyState readBody(BodyId id) const;
  /// Every particle, each body's consecutively in the order the bodies were added; the position
  /// in this list is the particle index that ContactRecord uses.
  std::vector<ParticleState> readParticles() const;
  std::vector<ContactRecord> readContacts() const;
  /// Counts, energies and the peak overlap (WorldStats); changes nothing, so two calls in a row
  /// agree. A sync point, unless nothing it reads has changed since the last call (the second of
  /// two in a row, or after a step of sleeping sand), which it then repeats.
  WorldStats readStats();
  /// The peak overlap of WorldStats::maxOverlap restarts at zero (step() does this at the start
  /// of every frame, so that a frame's stats hold that frame's peak).
  void resetPeakOverlap();
  /// Every body slot in use exactly as stored (what readStateHash covers), with the step count
  /// and simulated time; WorldSnapshot::frame is left 0 for the caller. Sync point.
  WorldSnapshot readSnapshot() const;
  /// A 64-bit hash of every body slot in use, bit for bit as stored (position, orientation,
  /// velocity, angular velocity, alive and calm count), reduced on the GPU with integer sums so
  /// that it does not depend on thread order; stateHash(readSnapshot()) gives the same. A change of
  /// any bit of one body always changes it. Sync point: 256 bytes, meant once per frame of a
  /// recording.
  std::uint64_t readStateHash();
  /// The sand's force and torque on every body that is neither a granule nor static, summed over
  /// the substeps since the previous call (or the body's creation), in the order the bodies were
  /// added; the sums restart at zero. Sync point: 32 bytes per such body, meant once per frame
  /// (e.g. by an engine bridge that applies them to its own bodies).
  std::vector<BodyForce> takeBodyForces();
  /// Per-kernel GPU times of the last step (empty unless profileKernels). Sync point.
  std::vector<KernelTime> kernelTimes() const;
  /// Turns WorldSettings::profileKernels on or off from the next step, e.g. to time a span
  /// without the queries' cost and then profile another. Off, kernelTimes() is empty.
  void setProfileKernels(bool enabled);

  /// Internal; opaque outside the library.
  struct Impl;

 private:
  friend struct detail::WorldAccess;  // gl_interop.h and the test suite
  Impl& impl();
  const Impl& impl() const;

  std::unique_ptr<Impl> m_impl;
};

}  // namespace sandphys
