#include "measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

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

SizeResult measureSize(const GpuContext& gpu, const SizePlan& plan, const MeasureOptions& options) {
  SizeResult result;
  result.plan = plan;
  result.loadBefore = loadAverage();

  const std::unique_ptr<BenchPile> pilePointer = makePile(options, plan.granules);
  const BenchPile& pile = *pilePointer;
  const float d = pile.particleDiameter();
  result.layout = pile.layout();

  const Clock::time_point setupStart = Clock::now();
  WorldSettings settings = pile.settings();
  settings.profileKernels = false;  // the timed substeps run without timer queries
  settings.statsEachFrame = false;  // substep() is used; stats are read when needed
  if (options.reserveParticles > settings.maxParticles) {
    settings.maxParticles = options.reserveParticles;
    settings.maxBodies = std::max(settings.maxBodies, options.reserveParticles / 4u);
  }
  settings.listSkin = options.listSkin * d;
  settings.sleep.enabled = options.sleep;
  const std::vector<Vec3> rock =
      options.rockSpeed > 0.0f ? ballOffsets(kRockRadius, d) : std::vector<Vec3>{};
  settings.maxBodies += options.rockSpeed > 0.0f ? 1u : 0u;
  settings.maxParticles += std::uint32_t(rock.size());
  const SandboxScript sandbox{};
  if (options.sandboxSeconds > 0.0) {
    settings.maxBodies += sandboxBodies();
    settings.maxParticles += sandboxParticles(sandbox, d);
  }
  World world(gpu, settings);
  pile.build(world);
  result.setupSeconds = secondsSince(setupStart);
  result.granules = world.granulesSpawned();
  result.particles = world.particleCount();
  result.floorParticles = result.particles - 4 * result.granules;
  result.particleCapacity = world.particleCapacity();
  result.timeStep = world.timeStep();
  result.contactTime = world.contactModel().contactTime;
  result.listSkin = world.contactModel().listSkin;
  result.gpuMemoryBytes = world.gpuMemoryBytes();
  result.built = readPileState(world, pile, world.readStats());
  world.resetPeakOverlap();  // the settled state's peak is the settling's

  char tagText[24];
  std::snprintf(tagText, sizeof tagText, "[%u]", result.granules);
  const auto tag = [&] { return std::string(tagText); };
  if (options.progress) {
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
                 tag().c_str(), result.setupSeconds, result.granules, result.layout.columns,
                 result.layout.fullLayers, result.layout.topLayerGranules,
                 result.layout.columnTop / d, container, double(result.timeStep));
  }

  // Settle, or restore the pile an earlier run settled with the same options (--pile-cache).
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
      std::fprintf(stderr, "%s settled pile restored from %s\n", tag().c_str(),
                   cacheFile.string().c_str());
    }
  } else {
    settle(world, plan, options, tag(), result);
    if (!cacheFile.empty() && !result.settleBudgetHit) {
      peakBefore = world.readStats().maxOverlap / d;  // also waits for the GPU
      saveSettledPile(
          cacheFile, cacheKey,
          {result.settleSteps, result.sleepWaitSteps, secondsSince(settleStart), peakBefore},
          world);
    }
  }
  // One substep more, restored or not, so that both start timing from the same state: llvmpipe
  // compiles each kernel at its first dispatch, and a restored World builds every list at its
  // first substep; neither is timed.
  world.substep(1);
  ++result.settleSteps;
  const WorldStats settledStats = world.readStats();  // also waits for the GPU
  result.asleepAtStart = settledStats.granulesAsleep;
  result.settleWallSeconds = secondsSince(settleStart);
  result.settled = readPileState(world, pile, settledStats);
  result.settled.maxOverlap = std::max(result.settled.maxOverlap, peakBefore);
  world.resetPeakOverlap();  // the end state's peak is the measured span's
  // The pile as timing starts, for the Worlds of the kernel versions compared.
  std::optional<WorldSnapshot> timingStart;
  if (!options.compareShaders.empty()) timingStart = world.readSnapshot();
  if (options.rockSpeed > 0.0f) {
    const float side = result.layout.boxSide * d;
    const Vec3 at{-0.5f * side + (kRockRadius + 2.0f) * d,
                  float(result.settled.pileTop) * d + (kRockRadius + 0.5f) * d, 0.0f};
    const float density = settings.material.density;
    world.addBody(makeParticleTemplate(rock, d, density),
                  {at,
                   {},
                   {options.rockSpeed, 0.0f, 0.0f},
                   {0.0f, 0.0f, -options.rockSpeed / (kRockRadius * d)},
                   Motion::Dynamic});
    result.rockParticles = std::uint32_t(rock.size());
  }

  // LAMMPS runs the same pile after sandphys, from a deck of it as timing starts (a read-back).
  const std::filesystem::path lammpsDeck =
      std::filesystem::absolute(options.lammpsDir) /
      (std::string(benchSceneName(options.scene)) + "-" + std::to_string(plan.granules));
  // In rounds, LAMMPS runs a round's steps after each of sandphys's (the clocks stopped).
  const std::uint32_t rounds = options.lammpsRanks.empty() ? 1u : options.lammpsRounds;
  const std::uint32_t roundSteps = plan.steps / rounds;
  if (!options.lammpsRanks.empty()) exportForLammps(world, lammpsDeck, roundSteps);
  for (const int ranks : options.lammpsRanks) {
    result.lammps.push_back({.ranks = ranks, .deck = lammpsDeck.string()});
  }
  const auto runLammpsRounds = [&] {
    for (LammpsTiming& run : result.lammps) runLammpsRound(roundSteps, world.timeStep(), run);
  };

  // Measure: whole chunks of substeps, timed from a synchronised start to a synchronised end;
  // or the sandbox script's frames.
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
    world.substep(count);
    result.steps += count;
    if (rounds > 1 && result.steps == roundEnd && roundEnd < plan.steps) {
      world.readStateHash();  // the sync that ends the round
      const double roundSeconds = secondsSince(start);
      result.roundWallSeconds.push_back(roundSeconds);
      result.wallSeconds += roundSeconds;
      result.cpuSeconds += processCpuSeconds() - cpuStart;
      runLammpsRounds();
      start = Clock::now();
      cpuStart = processCpuSeconds();
      roundEnd += roundSteps;
    }
    if (options.progress && secondsSince(lastProgress) >= kProgressInterval) {
      lastProgress = Clock::now();
      std::fprintf(stderr, "%s measuring: %u/%u substeps, %.0f s wall\n", tag().c_str(),
                   result.steps, plan.steps, result.wallSeconds + secondsSince(start));
    }
  }
  const WorldStats endStats = world.readStats();  // the sync that ends the timed span
  result.asleepAtEnd = endStats.granulesAsleep;
  const double lastSeconds = secondsSince(start);
  if (rounds > 1) result.roundWallSeconds.push_back(lastSeconds);
  result.wallSeconds += lastSeconds;
  result.cpuSeconds += processCpuSeconds() - cpuStart;
  result.loadAfter = loadAverage();

  result.penetrationClamps = endStats.penetrationClamps - settledStats.penetrationClamps;
  result.contactSlotOverflows = endStats.contactSlotOverflows - settledStats.contactSlotOverflows;
  result.velocityClamps = endStats.velocityClamps - settledStats.velocityClamps;
  result.listBuilds = endStats.listBuilds - settledStats.listBuilds;
  result.stillGridBuilds = endStats.stillGridBuilds - settledStats.stillGridBuilds;
  result.movingGridParticles = endStats.movingGridParticles;
  result.listOverflows = endStats.neighbourListOverflows - settledStats.neighbourListOverflows;
  result.measured = readPileState(world, pile, endStats);
  if (options.kernelTimes) result.kernels = profileKernels(world, options);
  if (options.progress) {
    std::fprintf(stderr, "%s measured %u substeps in %.1f s: Cundall number %.3g\n", tag().c_str(),
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
                   tag().c_str(), comparePlan.folders.size(), comparePlan.rounds,
                   comparePlan.stepsPerRound);
    }
    result.shaderRuns = compareShaders(gpu, settings, pile, *timingStart, comparePlan);
  }
  // After the timed span, so that drawing never shares the machine with the substeps measured.
  result.renders = measureRender(world, pile.bounds(), options.render);
  if (options.progress && !result.renders.empty()) {
    std::fprintf(stderr, "%s rendered %dx%d at %zu quality presets\n", tag().c_str(),
                 options.render.width, options.render.height, result.renders.size());
  }
  runLammpsRounds();  // the last round, or the only one
  for (const LammpsTiming& run : result.lammps) {
    if (options.progress) {
      std::fprintf(stderr, "%s LAMMPS on %d rank(s): %s\n", tag().c_str(), run.ranks,
                   run.failure.empty()
                       ? (std::to_string(run.millisecondsPerStep()) + " ms per step").c_str()
                       : run.failure.c_str());
    }
  }
  return result;
}

}  // namespace sandphys::bench
