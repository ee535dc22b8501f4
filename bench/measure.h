#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "bench_pile.h"
#include "box_pile.h"
#include "dense_pile.h"
#include "kernel_times.h"
#include "lammps_side_by_side.h"
#include "render_measure.h"
#include "sandbox_timeline.h"
#include "shader_compare.h"

namespace sandphys::bench {

/// What to run for one pile size.
struct SizePlan {
  std::uint32_t granules = 0;
  /// Substeps the pile settles before it is measured (at least 1: the first dispatches compile
  /// the kernels on llvmpipe, which must not be timed).
  std::uint32_t settleSteps = 0;
  /// Substeps measured.
  std::uint32_t steps = 0;
};

/// Options shared by every size.
struct MeasureOptions {
  /// Which pile is measured: `pile` (cylinder) or `box`.
  BenchScene scene = BenchScene::Cylinder;
  /// Cylinder pile geometry; `granules` is taken from the SizePlan.
  DensePileConfig pile{};
  /// Box pile; `granules` is taken from the SizePlan.
  BoxPileConfig box{};
  /// Wall-time cap of the settling, s; 0 = none. Settling stops at whichever comes first.
  double settleBudgetSeconds = 0.0;
  /// Wall-time cap of the measurement, s; 0 = none (checked between chunks).
  double budgetSeconds = 0.0;
  /// Substeps per World::substep call, or per World::step frame with `frames` (and per
  /// timer-query collection).
  std::uint32_t chunk = 10;
  /// The timed substeps as a game runs them: World::step frames of `chunk` substeps, the
  /// statistics read after each (as WorldSettings::statsEachFrame does), so that frames of
  /// sleeping sand skip their idle substeps (SizeResult::idleSubsteps).
  bool frames = false;
  /// After the timed substeps, run `kernelSteps` more with per-kernel GL timer queries
  /// (World::setProfileKernels). The timed substeps run without them, whose cost they would carry.
  bool kernelTimes = true;
  std::uint32_t kernelSteps = 500;  ///< substeps the kernel times are averaged over
  /// Progress lines on stderr.
  bool progress = true;
  /// Time the renderer on the measured pile (off unless a size is given).
  RenderOptions render{};
  /// Particles (and a quarter as many bodies) the World reserves; 0 or fewer than the pile
  /// needs: exactly what it needs. What a game reserving room for more costs.
  std::uint32_t reserveParticles = 0;
  /// Skin of the neighbour lists in particle diameters (WorldSettings::listSkin); 0: derived.
  float listSkin = 0.0f;
  /// Substeps between sorts of the granules by place (WorldSettings::sortInterval); 0: derived.
  std::uint32_t sortInterval = 0;
  /// The pile's granules added in a random order (the same poses): sand whose order in memory
  /// no longer follows place, as after a long flow.
  bool shuffled = false;
  /// Sleeping sand (WorldSettings::sleep): after the settling, substeps run until every granule
  /// sleeps (at most sleepWaitFactor sleep times), then the timed ones.
  bool sleep = false;
  double sleepWaitFactor = 4.0;
  /// A ball (radius kRockRadius d, particles on a lattice of spacing d) set down on the pile
  /// near one wall at the start of timing, rolling across it at this speed (m/s; 0: no ball):
  /// the timed substeps then cost what the sand it disturbs costs.
  float rockSpeed = 0.0f;
  /// Box: instead of the timed substeps, this many simulated seconds of SandboxScript (a ball
  /// dropped, a pusher ploughing), each frame timed (SizeResult::timeline); 0: off.
  double sandboxSeconds = 0.0;
  /// Folder of settled piles (--pile-cache; empty: none): a pile settled there before is restored
  /// instead of settled again, and one settled now is kept there (pile_cache.h).
  std::string pileCache;
  /// MPI ranks of the LAMMPS runs of each size's pile, one run per entry (empty: none): the World
  /// as timing starts, exported (exportLammps) into lammpsDir/<scene>-<granules> and run for the
  /// timed substeps after sandphys's (SizeResult::lammps).
  std::vector<int> lammpsRanks;
  std::string lammpsDir = "bench-lammps";
  /// With lammpsRanks: the timed substeps in this many rounds of equal length, each followed by
  /// LAMMPS runs of as many steps from the deck, so that the two alternate on the machine and its
  /// drift falls on both (SizeResult::medianRoundSpeedAgainst); 1: LAMMPS after all of them.
  std::uint32_t lammpsRounds = 1;
  /// Kernel versions (shader folders, or kBuiltInShaders) run from the pile as timing starts, in
  /// one process, `compareRounds` rounds of each in turn after the timed substeps
  /// (SizeResult::shaderRuns; empty: none).
  std::vector<std::string> compareShaders;
  std::uint32_t compareRounds = 10;
};
inline constexpr float kRockRadius = 3.0f;  // d

/// How settled the pile is at one moment (one readStats and one readBodies, both sync points).
struct PileState {
  double simulatedSeconds = 0.0;  ///< since the pile was built, s
  std::uint32_t contacts = 0;     ///< particle pairs + collider contacts of the last substep
  double contactsPerGranule = 0.0;
  double kineticEnergyPerGranule = 0.0;  ///< J
  double rmsSpeed = 0.0;                 ///< sqrt(2 KE / (granules · granule mass)), m/s
  double maxOverlap = 0.0;               ///< largest overlap of the phase that ends here, d
  double pileTop = 0.0;                  ///< CylinderPile::pileTop, d
  std::uint32_t granulesOutside = 0;     ///< granule centres outside the container
};

/// Everything measured for one size.
struct SizeResult {
  SizePlan plan{};
  std::uint32_t granules = 0;
  std::uint32_t particles = 0;         ///< granule particles + rough floor particles
  std::uint32_t floorParticles = 0;    ///< 0 in the box, whose floor is a flat face
  std::uint32_t particleCapacity = 0;  ///< the World's WorldSettings::maxParticles
  PileLayout layout{};
  float timeStep = 0.0f;  ///< s
  /// Hertz contact time t_n at the speed guard (ContactModel::contactTime), s: the World
  /// refuses a time step above t_n / kMinStepsPerContact.
  float contactTime = 0.0f;
  /// Skin of the neighbour lists (ContactModel::listSkin) and its near skin
  /// (ContactModel::listNearSkin), m.
  float listSkin = 0.0f;
  float listNearSkin = 0.0f;
  double setupSeconds = 0.0;  ///< World creation (kernel compilation) and build, wall s
  std::uint64_t gpuMemoryBytes = 0;
  std::vector<BufferMemory> gpuMemoryByBuffer;  ///< World::gpuMemoryByBuffer

  std::uint32_t settleSteps = 0;  ///< substeps actually run before measuring
  /// MeasureOptions::sleep: substeps run after the settling until all slept (or the wait ran
  /// out), and the sleeping granules at the start and the end of the timed span.
  std::uint32_t sleepWaitSteps = 0;
  std::uint32_t asleepAtStart = 0;
  std::uint32_t asleepAtEnd = 0;
  /// MeasureOptions::sleep: the list builds of the timed span that sorted the sleepers again
  /// (WorldStats::stillGridBuilds), and the particles the last build sorted into its moving grid.
  std::uint64_t stillGridBuilds = 0;
  std::uint32_t movingGridParticles = 0;
  /// MeasureOptions::frames: the timed substeps that frames of sleeping sand skipped
  /// (StepReport::idleSubsteps).
  std::uint64_t idleSubsteps = 0;
  /// MeasureOptions::frames: the wall time of each frame that skipped its idle substeps, its
  /// statistics read included (ms).
  std::vector<double> idleFrameMs;
  /// MeasureOptions::rock: the ball's particles (0 without).
  std::uint32_t rockParticles = 0;
  /// MeasureOptions::sandboxSeconds: every frame of the script (empty without).
  std::vector<TimelineFrame> timeline;
  double settleWallSeconds = 0.0;
  bool settleBudgetHit = false;
  /// MeasureOptions::pileCache: the file the settled pile was restored from (empty: it settled in
  /// this run; settleWallSeconds is then the restore's, and the settling's that of the run that
  /// wrote the file is settledFromWallSeconds).
  std::string settledFrom;
  double settledFromWallSeconds = 0.0;
  PileState built{};     ///< right after build
  PileState settled{};   ///< when the measurement starts
  PileState measured{};  ///< when it ends

  std::uint32_t steps = 0;   ///< substeps measured
  double wallSeconds = 0.0;  ///< wall time of those substeps (ends with a sync)
  /// With MeasureOptions::lammpsRounds above 1: the wall time of each round, s (each ends with a
  /// sync; wallSeconds is their sum).
  std::vector<double> roundWallSeconds;
  double cpuSeconds = 0.0;  ///< process CPU time over the same span (all threads)
  bool budgetHit = false;
  std::uint64_t penetrationClamps = 0;     ///< during the measurement (ContactLaw::PaperViscous)
  std::uint64_t contactSlotOverflows = 0;  ///< during the measurement (HertzMindlin)
  std::uint64_t velocityClamps = 0;        ///< during the measurement
  std::uint64_t listBuilds = 0;            ///< neighbour-list builds during the measurement
  std::uint64_t listNearMarkings = 0;      ///< markings of the lists' near part, the same span
  std::uint64_t listOverflows = 0;         ///< particles over a list's capacity at those builds
  std::vector<KernelStep> kernels;         ///< empty without kernel times
  std::vector<RenderTiming> renders;       ///< one per quality preset; empty without --render
  std::vector<LammpsTiming> lammps;        ///< one per MeasureOptions::lammpsRanks entry
  std::vector<ShaderRun> shaderRuns;       ///< one per MeasureOptions::compareShaders folder
  double loadBefore = -1.0;  ///< 1-minute load average before the size ran (-1: unknown)
  double loadAfter = -1.0;

  double cundallNumber() const;  ///< granule-steps per wall second
  double microsecondsPerGranuleStep() const;
  double simulatedPerWallSecond() const;
  double wallMillisecondsPerStep() const;
  double cpuMillisecondsPerStep() const;
  double kernelMillisecondsPerStep() const;  ///< sum over kernels
  /// Particle-steps per wall second: every particle the World steps (the floor's included).
  double particleStepsPerSecond() const;
  /// Contacts (World stats at the end of the timed substeps) per particle.
  double contactsPerParticle() const;
  /// Wall time per substep over the contacts at the end of the timed substeps, µs; 0 without
  /// contacts.
  double microsecondsPerParticleContact() const;
  /// GL compute dispatches per substep, summed over kernels (from the kernel profiler), the
  /// list build's indirect ones included whether or not a build was due; 0 without kernel times.
  double dispatchesPerStep() const;
  /// Builds of the neighbour lists per 1000 measured substeps (WorldStats::listBuilds).
  double listBuildsPer1000Steps() const;
  /// How many times faster per step sandphys ran than `run` of its pile (below 1: slower).
  double speedAgainst(const LammpsTiming& run) const;
  /// The same round by round (rounds of equal length, MeasureOptions::lammpsRounds): the median
  /// of the rounds' ratios; speedAgainst when there are no rounds to pair (or the budget cut one).
  double medianRoundSpeedAgainst(const LammpsTiming& run) const;
};

/// The pile `options` selects (the cylinder's DensePile or the BoxPile), of `granules` granules.
/// Throws InvalidArgument as their constructors do.
std::unique_ptr<BenchPile> makePile(const MeasureOptions& options, std::uint32_t granules);

/// The particle diameter of the scene `options` selects, m.
float particleDiameter(const MeasureOptions& options);

/// Builds the pile of `plan.granules` granules in a fresh World on `gpu`, settles it and measures
/// it. Throws sandphys::Error from World setup.
SizeResult measureSize(const GpuContext& gpu, const SizePlan& plan, const MeasureOptions& options);

/// The 1-minute load average of the machine, or -1 where /proc/loadavg is missing.
double loadAverage();

}  // namespace sandphys::bench
