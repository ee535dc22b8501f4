#include "measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <variant>

#include "pile_cache.h"
#include "timing.h"

namespace sandphys::bench {

namespace {

// Seconds between progress lines.
constexpr double kProgressInterval = 15.0;

PileState readPileState(World& world, const BenchPile& pile, const WorldStats& stats) {
  const double d = pile.particleDiameter();
  const double granules = pile.granules();
  PileState state;
  state.simulatedSeconds = world.simulatedTime();
  state.contacts = stats.contacts;
  state.contactsPerGranule = stats.contacts / granules;
  state.kineticEnergyPerGranule = stats.kineticEnergy / granules;
  state.rmsSpeed = std::sqrt(2.0 * state.kineticEnergyPerGranule / pile.granuleMass());
  state.maxOverlap = stats.maxOverlap / d;
  const std::vector<BodyState> bodies = world.readBodies();
  state.pileTop = pile.pileTop(bodies) / d;
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule && !pile.contains(body.position)) {
      ++state.granulesOutside;
    }
  }
  return state;
}

// Per-kernel GPU time per substep over options.kernelSteps further substeps, with the timer
// queries on (and off again after them).
std::vector<KernelStep> profileKernels(World& world, const MeasureOptions& options) {
  std::vector<KernelStep> kernels;
  world.setProfileKernels(true);
  for (std::uint32_t steps = 0; steps < options.kernelSteps;) {
    const std::uint32_t count = std::min(options.chunk, options.kernelSteps - steps);
    world.substep(count);
    steps += count;
    // Timer queries are collected inside substep(); this only copies the totals.
    accumulateKernels(kernels, world.kernelTimes());
  }
  world.setProfileKernels(false);
  divideBySteps(kernels, options.kernelSteps);
  return kernels;
}

// Settles the pile in `world`: plan.settleSteps substeps (at least one: llvmpipe compiles each
// kernel at its first dispatch) or until the settle budget runs out, then with sleep until every
// granule sleeps or the wait runs out.
void settle(World& world, const SizePlan& plan, const MeasureOptions& options,
            const std::string& tag, SizeResult& result) {
  const std::uint32_t settleSteps = std::max<std::uint32_t>(plan.settleSteps, 1);
  const Clock::time_point settleStart = Clock::now();
  Clock::time_point lastProgress = settleStart;
  while (result.settleSteps < settleSteps) {
    if (options.settleBudgetSeconds > 0.0 && result.settleSteps > 0 &&
        secondsSince(settleStart) >= options.settleBudgetSeconds) {
      result.settleBudgetHit = true;
      break;
    }
    const std::uint32_t count = std::min(options.chunk, settleSteps - result.settleSteps);
    world.substep(count);
    result.settleSteps += count;
    if (options.progress && secondsSince(lastProgress) >= kProgressInterval) {
      lastProgress = Clock::now();
      const WorldStats stats = world.readStats();
      std::fprintf(stderr,
                   "%s settling: %u/%u substeps, %.0f s wall, %.4f s simulated, KE/granule "
                   "%.3g J, contacts/granule %.2f\n",
                   tag.c_str(), result.settleSteps, settleSteps, secondsSince(settleStart),
                   world.simulatedTime(), stats.kineticEnergy / result.granules,
                   double(stats.contacts) / result.granules);
    }
  }
  if (options.sleep) {
    const auto wait = std::uint32_t(options.sleepWaitFactor * world.sleepModel().substeps);
    while (result.sleepWaitSteps < wait && world.readStats().granulesAsleep < result.granules) {
      world.substep(options.chunk);
      result.sleepWaitSteps += options.chunk;
    }
  }
}

}  // namespace

double SizeResult::cundallNumber() const {
  return wallSeconds > 0.0 ? double(granules) * steps / wallSeconds : 0.0;
}

double SizeResult::microsecondsPerGranuleStep() const {
  const double cundall = cundallNumber();
  return cundall > 0.0 ? 1.0e6 / cundall : 0.0;
}

double SizeResult::simulatedPerWallSecond() const {
  return wallSeconds > 0.0 ? double(steps) * timeStep / wallSeconds : 0.0;
}

double SizeResult::wallMillisecondsPerStep() const {
  return steps > 0 ? 1.0e3 * wallSeconds / steps : 0.0;
}

double SizeResult::cpuMillisecondsPerStep() const {
  return steps > 0 ? 1.0e3 * cpuSeconds / steps : 0.0;
}

double SizeResult::kernelMillisecondsPerStep() const {
  double sum = 0.0;
  for (const KernelStep& kernel : kernels) sum += kernel.millisecondsPerStep;
  return sum;
}

double SizeResult::particleStepsPerSecond() const {
  return wallSeconds > 0.0 ? double(particles) * steps / wallSeconds : 0.0;
}

double SizeResult::contactsPerParticle() const {
  return particles > 0 ? double(measured.contacts) / particles : 0.0;
}

double SizeResult::microsecondsPerParticleContact() const {
  return measured.contacts > 0 ? 1.0e3 * wallMillisecondsPerStep() / measured.contacts : 0.0;
}

double SizeResult::dispatchesPerStep() const {
  double sum = 0.0;
  for (const KernelStep& kernel : kernels) sum += kernel.dispatchesPerStep;
  return sum;
}

double SizeResult::listBuildsPer1000Steps() const {
  return steps > 0 ? 1000.0 * double(listBuilds) / steps : 0.0;
}

double SizeResult::speedAgainst(const LammpsTiming& run) const {
  return wallMillisecondsPerStep() > 0.0 ? run.millisecondsPerStep() / wallMillisecondsPerStep()
                                         : 0.0;
}

double SizeResult::medianRoundSpeedAgainst(const LammpsTiming& run) const {
  // A budget that cut the last round short leaves rounds of unequal length.
  if (budgetHit || roundWallSeconds.size() < 2 ||
      run.roundLoopSeconds.size() != roundWallSeconds.size()) {
    return speedAgainst(run);
  }
  std::vector<double> ratios;
  for (std::size_t r = 0; r < roundWallSeconds.size(); ++r) {
    ratios.push_back(run.roundLoopSeconds[r] / roundWallSeconds[r]);
  }
  return median(ratios);
}

std::unique_ptr<BenchPile> makePile(const MeasureOptions& options, std::uint32_t granules) {
  if (options.scene == BenchScene::Box) {
    BoxPileConfig config = options.box;
    config.granules = granules;
    return std::make_unique<BoxPile>(config);
  }
  DensePileConfig config = options.pile;
  config.granules = granules;
  return std::make_unique<DensePile>(config);
}

float particleDiameter(const MeasureOptions& options) {
  return options.scene == BenchScene::Box ? options.box.particleDiameter
                                          : options.pile.particleDiameter;
}

double loadAverage() {
  std::ifstream file("/proc/loadavg");
  double load = -1.0;
  if (!(file >> load)) return -1.0;
  return load;
}

namespace {

// The pile's settings as the timing runs them: no timer queries, statistics when read, the
// options' skin, sleep and reserve, and room for the rock and the sandbox script's bodies.
WorldSettings timedSettings(const BenchPile& pile, const MeasureOptions& options,
                            std::uint32_t rockParticles, const SandboxScript& sandbox) {
  const float d = pile.particleDiameter();
  WorldSettings settings = pile.settings();
  settings.profileKernels = false;
  settings.statsEachFrame = false;
  if (options.reserveParticles > settings.maxParticles) {
    settings.maxParticles = options.reserveParticles;
    settings.maxBodies = std::max(settings.maxBodies, options.reserveParticles / 4u);
  }
  settings.listSkin = options.listSkin * d;
  settings.sortInterval = options.sortInterval;
  settings.sleep.enabled = options.sleep;
  settings.maxBodies += rockParticles > 0 ? 1u : 0u;
  settings.maxParticles += rockParticles;
  if (options.sandboxSeconds > 0.0) {
    settings.maxBodies += sandboxBodies();
    settings.maxParticles += sandboxParticles(sandbox, d);
  }
  return settings;
}

void printBuilt(const std::string& tag, const SizeResult& result, float d) {
  char container[64] = "";
  if (result.layout.boxSide > 0.0f) {
    std::snprintf(container, sizeof container, " in a box of %.1f d x %.0f d",
                  double(result.layout.boxSide), double(result.layout.wallHeight));
  } else if (result.layout.wallRaised) {
    std::snprintf(container, sizeof container, " (wall raised)");
  }
  std::fprintf(stderr,
               "%s built in %.1f s: %u granules in %u columns x %u layers (+%u), column top "
               "%.1f d%s; dt %.3g s\n",
               tag.c_str(), result.setupSeconds, result.granules, result.layout.columns,
               result.layout.fullLayers, result.layout.topLayerGranules,
               result.layout.columnTop / d, container, double(result.timeStep));
}

// Builds `pile` in `world`, or with --shuffle the same colliders and granules, the granules in a
// random order: the pile is built in a World of its own, whose granules are then added to `world`
// shuffled.
void buildPile(const GpuContext& gpu, const BenchPile& pile, const MeasureOptions& options,
               World& world) {
  if (!options.shuffled) {
    pile.build(world);
    return;
  }
  World built(gpu, world.settings());
  pile.build(built);
  for (const ColliderShape& shape : built.colliders()) {
    std::visit([&](const auto& collider) { world.addCollider(collider); }, shape);
  }
  std::vector<BodyDesc> granules;
  for (const BodyState& body : built.readBodies()) {
    if (!body.granule)
      throw InvalidArgument("--shuffle: the pile holds bodies that are not granules");
    granules.push_back(
        {body.position, body.orientation, body.velocity, body.angularVelocity, body.motion});
  }
  std::shuffle(granules.begin(), granules.end(), std::mt19937_64(0x5eed));
  world.addGranules(granules);
}

// Settles the pile, or restores the one an earlier run settled with the same options
// (--pile-cache), then runs one substep more either way, so that both start timing from the same
// state: llvmpipe compiles each kernel at its first dispatch, and a restored World builds every
// list at its first substep; neither is timed. Returns the statistics then.
WorldStats settleOrRestore(World& world, const BenchPile& pile, const SizePlan& plan,
                           const MeasureOptions& options, const std::string& tag,
                           SizeResult& result) {
  const Clock::time_point settleStart = Clock::now();
  std::string cacheKey;
  std::filesystem::path cacheFile;
  std::optional<SettledPile> cached;
  if (!options.pileCache.empty()) {
    cacheKey = settledPileKey(options, plan, world);
    cacheFile = settledPileFile(options.pileCache, options, plan.granules, cacheKey);
    cached = loadSettledPile(cacheFile, cacheKey, world);
  }
  // The largest overlap of the settling before the last substep (readStats takes it).
  double peakBefore = 0.0;
  if (cached) {
    result.settleSteps = cached->settleSteps;
    result.sleepWaitSteps = cached->sleepWaitSteps;
    result.settledFrom = cacheFile.string();
    result.settledFromWallSeconds = cached->settleWallSeconds;
    peakBefore = cached->peakOverlap;
    if (options.progress) {
      std::fprintf(stderr, "%s settled pile restored from %s\n", tag.c_str(),
                   cacheFile.string().c_str());
    }
  } else {
    settle(world, plan, options, tag, result);
    if (!cacheFile.empty() && !result.settleBudgetHit) {
      peakBefore = world.readStats().maxOverlap / pile.particleDiameter();  // waits for the GPU
      saveSettledPile(
          cacheFile, cacheKey,
          {result.settleSteps, result.sleepWaitSteps, secondsSince(settleStart), peakBefore},
          world);
    }
  }
  world.substep(1);
  ++result.settleSteps;
  const WorldStats settledStats = world.readStats();  // also waits for the GPU
  result.asleepAtStart = settledStats.granulesAsleep;
  result.settleWallSeconds = secondsSince(settleStart);
  result.settled = readPileState(world, pile, settledStats);
  result.settled.maxOverlap = std::max(result.settled.maxOverlap, peakBefore);
  world.resetPeakOverlap();  // the end state's peak is the measured span's
  return settledStats;
}

// MeasureOptions::rockSpeed: the ball `rock` (offsets, m), set down on the settled pile by the
// wall at x < 0, rolling towards +x.
void addRock(World& world, const std::vector<Vec3>& rock, const MeasureOptions& options,
             SizeResult& result, float d) {
  const float side = result.layout.boxSide * d;
  const Vec3 at{-0.5f * side + (kRockRadius + 2.0f) * d,
                float(result.settled.pileTop) * d + (kRockRadius + 0.5f) * d, 0.0f};
  world.addBody(makeParticleTemplate(rock, d, world.settings().material.density),
                {at,
                 {},
                 {options.rockSpeed, 0.0f, 0.0f},
                 {0.0f, 0.0f, -options.rockSpeed / (kRockRadius * d)},
                 Motion::Dynamic});
  result.rockParticles = std::uint32_t(rock.size());
}

// The timed substeps: whole chunks, timed from a synchronised start to a synchronised end, in
// `rounds` rounds with `betweenRounds` run between them (the clocks stopped); or the sandbox
// script's frames. Ends with a sync; returns the statistics then.
template <class BetweenRounds>
WorldStats timeSubsteps(World& world, const SizePlan& plan, const MeasureOptions& options,
                        const SandboxScript& sandbox, std::uint32_t rounds, float d,
                        const std::string& tag, BetweenRounds betweenRounds, SizeResult& result) {
  const std::uint32_t roundSteps = plan.steps / rounds;
  Clock::time_point start = Clock::now();
  double cpuStart = processCpuSeconds();
  Clock::time_point lastProgress = start;
  std::uint32_t roundEnd = roundSteps;
  if (options.sandboxSeconds > 0.0) {
    const double before = world.simulatedTime();
    result.timeline = runSandbox(world, sandbox, result.layout.boxSide * d,
                                 float(result.settled.pileTop) * d, options.sandboxSeconds);
    result.steps = std::uint32_t(std::llround((world.simulatedTime() - before) / world.timeStep()));
  }
  while (options.sandboxSeconds <= 0.0 && result.steps < plan.steps) {
    if (options.budgetSeconds > 0.0 && result.steps > 0 &&
        result.wallSeconds + secondsSince(start) >= options.budgetSeconds) {
      result.budgetHit = true;
      break;
    }
    const std::uint32_t count = std::min(options.chunk, roundEnd - result.steps);
    if (options.frames) {
      // A frame a hair longer than `count` substeps, stopped at exactly `count`.
      const float frameDt = std::nextafter(float(double(count) * world.timeStep()),
                                           std::numeric_limits<float>::max());
      const Clock::time_point frameStart = Clock::now();
      const StepReport frame = world.step(frameDt, world.stepCount() + count);
      world.readStats();
      result.steps += frame.substeps;
      result.idleSubsteps += frame.idleSubsteps;
      if (frame.idleSubsteps > 0) result.idleFrameMs.push_back(1e3 * secondsSince(frameStart));
    } else {
      world.substep(count);
      result.steps += count;
    }
    if (rounds > 1 && result.steps == roundEnd && roundEnd < plan.steps) {
      world.readStateHash();  // the sync that ends the round
      const double roundSeconds = secondsSince(start);
      result.roundWallSeconds.push_back(roundSeconds);
      result.wallSeconds += roundSeconds;
      result.cpuSeconds += processCpuSeconds() - cpuStart;
      betweenRounds();
      start = Clock::now();
      cpuStart = processCpuSeconds();
      roundEnd += roundSteps;
    }
    if (options.progress && secondsSince(lastProgress) >= kProgressInterval) {
      lastProgress = Clock::now();
      std::fprintf(stderr, "%s measuring: %u/%u substeps, %.0f s wall\n", tag.c_str(), result.steps,
                   plan.steps, result.wallSeconds + secondsSince(start));
    }
  }
  const WorldStats endStats = world.readStats();  // the sync that ends the timed span
  const double lastSeconds = secondsSince(start);
  if (rounds > 1) result.roundWallSeconds.push_back(lastSeconds);
  result.wallSeconds += lastSeconds;
  result.cpuSeconds += processCpuSeconds() - cpuStart;
  return endStats;
}

// What the World counted over the timed span, from the statistics at its start and its end.
void countTimedSpan(const WorldStats& start, const WorldStats& end, SizeResult& result) {
  result.asleepAtEnd = end.granulesAsleep;
  result.penetrationClamps = end.penetrationClamps - start.penetrationClamps;
  result.contactSlotOverflows = end.contactSlotOverflows - start.contactSlotOverflows;
  result.velocityClamps = end.velocityClamps - start.velocityClamps;
  result.listBuilds = end.listBuilds - start.listBuilds;
  result.listNearMarkings = end.listNearMarkings - start.listNearMarkings;
  result.stillGridBuilds = end.stillGridBuilds - start.stillGridBuilds;
  result.movingGridParticles = end.movingGridParticles;
  result.listOverflows = end.neighbourListOverflows - start.neighbourListOverflows;
}

}  // namespace

SizeResult measureSize(const GpuContext& gpu, const SizePlan& plan, const MeasureOptions& options) {
  SizeResult result;
  result.plan = plan;
  result.loadBefore = loadAverage();

  const std::unique_ptr<BenchPile> pilePointer = makePile(options, plan.granules);
  const BenchPile& pile = *pilePointer;
  const float d = pile.particleDiameter();
  result.layout = pile.layout();

  const Clock::time_point setupStart = Clock::now();
  const std::vector<Vec3> rock =
      options.rockSpeed > 0.0f ? ballOffsets(kRockRadius, d) : std::vector<Vec3>{};
  const SandboxScript sandbox{};
  const WorldSettings settings = timedSettings(pile, options, std::uint32_t(rock.size()), sandbox);
  World world(gpu, settings);
  buildPile(gpu, pile, options, world);
  result.setupSeconds = secondsSince(setupStart);
  result.granules = world.granulesSpawned();
  result.particles = world.particleCount();
  result.floorParticles = result.particles - 4 * result.granules;
  result.particleCapacity = world.particleCapacity();
  result.timeStep = world.timeStep();
  result.contactTime = world.contactModel().contactTime;
  result.listSkin = world.contactModel().listSkin;
  result.listNearSkin = world.contactModel().listNearSkin;
  result.gpuMemoryBytes = world.gpuMemoryBytes();
  result.gpuMemoryByBuffer = world.gpuMemoryByBuffer();
  result.built = readPileState(world, pile, world.readStats());
  world.resetPeakOverlap();  // the settled state's peak is the settling's

  char tagText[24];  // snprintf: GCC 12 warns falsely (-Wrestrict) on "[" + to_string + "]"
  std::snprintf(tagText, sizeof tagText, "[%u]", result.granules);
  const std::string tag = tagText;
  if (options.progress) printBuilt(tag, result, d);
  const WorldStats settledStats = settleOrRestore(world, pile, plan, options, tag, result);
  // The pile as timing starts, for the Worlds of the kernel versions compared.
  std::optional<WorldSnapshot> timingStart;
  if (!options.compareShaders.empty()) timingStart = world.readSnapshot();
  if (options.rockSpeed > 0.0f) addRock(world, rock, options, result, d);

  // LAMMPS runs the same pile after sandphys, from a deck of it as timing starts (a read-back);
  // in rounds, a round's steps after each of sandphys's.
  const std::filesystem::path lammpsDeck =
      std::filesystem::absolute(options.lammpsDir) /
      (std::string(benchSceneName(options.scene)) + "-" + std::to_string(plan.granules));
  const std::uint32_t rounds = options.lammpsRanks.empty() ? 1u : options.lammpsRounds;
  const std::uint32_t roundSteps = plan.steps / rounds;
  if (!options.lammpsRanks.empty()) exportForLammps(world, lammpsDeck, roundSteps);
  for (const int ranks : options.lammpsRanks) {
    result.lammps.push_back({.ranks = ranks, .deck = lammpsDeck.string()});
  }
  const auto runLammpsRounds = [&] {
    for (LammpsTiming& run : result.lammps) runLammpsRound(roundSteps, world.timeStep(), run);
  };

  const WorldStats endStats =
      timeSubsteps(world, plan, options, sandbox, rounds, d, tag, runLammpsRounds, result);
  result.loadAfter = loadAverage();
  countTimedSpan(settledStats, endStats, result);
  result.measured = readPileState(world, pile, endStats);
  if (options.kernelTimes) result.kernels = profileKernels(world, options);
  if (options.progress) {
    std::fprintf(stderr, "%s measured %u substeps in %.1f s: Cundall number %.3g\n", tag.c_str(),
                 result.steps, result.wallSeconds, result.cundallNumber());
  }
  if (timingStart) {
    const ShaderComparePlan comparePlan{
        .folders = options.compareShaders,
        .rounds = options.compareRounds,
        .stepsPerRound = std::max(plan.steps / options.compareRounds, 1u),
        .chunk = options.chunk,
        .kernelTimes = options.kernelTimes};
    if (options.progress) {
      std::fprintf(stderr, "%s comparing %zu kernel versions: %u rounds of %u substeps each\n",
                   tag.c_str(), comparePlan.folders.size(), comparePlan.rounds,
                   comparePlan.stepsPerRound);
    }
    result.shaderRuns = compareShaders(gpu, settings, pile, *timingStart, comparePlan);
  }
  // After the timed span, so that drawing never shares the machine with the substeps measured.
  result.renders = measureRender(world, pile.bounds(), options.render);
  if (options.progress && !result.renders.empty()) {
    std::fprintf(stderr, "%s rendered %dx%d at %zu quality presets\n", tag.c_str(),
                 options.render.width, options.render.height, result.renders.size());
  }
  runLammpsRounds();  // the last round, or the only one
  for (const LammpsTiming& run : result.lammps) {
    if (options.progress) {
      std::fprintf(stderr, "%s LAMMPS on %d rank(s): %s\n", tag.c_str(), run.ranks,
                   run.failure.empty()
                       ? (std::to_string(run.millisecondsPerStep()) + " ms per step").c_str()
                       : run.failure.c_str());
    }
  }
  return result;
}

}  // namespace sandphys::bench
