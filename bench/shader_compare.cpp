#include "shader_compare.h"

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <optional>

#include "timing.h"

namespace sandphys::bench {

namespace {

// Sets SANDPHYS_SHADER_DIR for the Worlds made while it lives (unset for kBuiltInShaders), and
// puts back what was there.
class ShaderDirectory {
 public:
  explicit ShaderDirectory(const std::string& folder) {
    if (const char* before = std::getenv(kVariable)) m_before = before;
    if (folder == kBuiltInShaders) {
      unsetenv(kVariable);
    } else {
      setenv(kVariable, folder.c_str(), 1);
    }
  }
  ~ShaderDirectory() {
    if (m_before) {
      setenv(kVariable, m_before->c_str(), 1);
    } else {
      unsetenv(kVariable);
    }
  }
  ShaderDirectory(const ShaderDirectory&) = delete;
  ShaderDirectory& operator=(const ShaderDirectory&) = delete;

 private:
  static constexpr const char* kVariable = "SANDPHYS_SHADER_DIR";
  std::optional<std::string> m_before;
};

// A World of `version`'s kernels holding `pile` as it was at `start` (sorted by place in its first
// substep, for a version with kSortedSuffix).
std::unique_ptr<World> worldOf(const std::string& version, const GpuContext& gpu,
                               WorldSettings settings, const BenchPile& pile,
                               const WorldSnapshot& start) {
  try {
    bool sorted = false;
    const ShaderDirectory directory(versionFolder(version, &sorted));
    // A version either sorts once, in its first substep, or never, so that each round times one
    // order of the granules.
    settings.sortInterval = sorted ? std::uint32_t(start.steps + 1) : kNeverSortGranules;
    auto world = std::make_unique<World>(gpu, settings);
    pile.build(*world);
    world->restoreSnapshot(start);
    return world;
  } catch (const Error& error) {
    throw Error("--compare-shaders " + version + ": " + error.what());
  }
}

// Runs `steps` substeps of `world` in calls of `chunk`, adding each call's kernel times to
// `kernels` when given.
void run(World& world, std::uint32_t steps, std::uint32_t chunk,
         std::vector<KernelStep>* kernels = nullptr) {
  for (std::uint32_t done = 0; done < steps;) {
    const std::uint32_t count = std::min(chunk, steps - done);
    world.substep(count);
    done += count;
    if (kernels) accumulateKernels(*kernels, world.kernelTimes());
  }
}

}  // namespace

std::string versionFolder(const std::string& version, bool* sorted) {
  const bool hasSuffix = version.ends_with(kSortedSuffix);
  if (sorted) *sorted = hasSuffix;
  return hasSuffix ? version.substr(0, version.size() - kSortedSuffix.size()) : version;
}

double ShaderRun::medianMilliseconds() const {
  return median(roundMilliseconds);
}

double ShaderRun::fastestMilliseconds() const {
  return roundMilliseconds.empty()
             ? 0.0
             : *std::min_element(roundMilliseconds.begin(), roundMilliseconds.end());
}

double ShaderRun::cpuMillisecondsPerStep() const {
  return steps > 0 ? 1e3 * cpuSeconds / steps : 0.0;
}

std::vector<ShaderRun> compareShaders(const GpuContext& gpu, const WorldSettings& settings,
                                      const BenchPile& pile, const WorldSnapshot& start,
                                      const ShaderComparePlan& plan) {
  std::vector<std::unique_ptr<World>> worlds;
  std::vector<ShaderRun> runs;
  for (const std::string& folder : plan.folders) {
    worlds.push_back(worldOf(folder, gpu, settings, pile, start));
    worlds.back()->setProfileKernels(plan.kernelTimes);
    run(*worlds.back(), plan.warmupSteps, plan.chunk);
    worlds.back()->readStateHash();  // waits for the GPU
    runs.push_back({.folder = folder});
  }
  for (std::uint32_t round = 0; round < plan.rounds; ++round) {
    for (std::size_t turn = 0; turn < worlds.size(); ++turn) {
      // Every other round the other way round: no version always runs right after another.
      const std::size_t i = round % 2 == 0 ? turn : worlds.size() - 1 - turn;
      const Clock::time_point wallStart = Clock::now();
      const double cpuStart = processCpuSeconds();
      run(*worlds[i], plan.stepsPerRound, plan.chunk,
          plan.kernelTimes ? &runs[i].kernels : nullptr);
      runs[i].stateHash = worlds[i]->readStateHash();  // the sync that ends the round
      runs[i].roundMilliseconds.push_back(1e3 * secondsSince(wallStart) / plan.stepsPerRound);
      runs[i].cpuSeconds += processCpuSeconds() - cpuStart;
      runs[i].steps += plan.stepsPerRound;
    }
  }
  for (ShaderRun& version : runs) divideBySteps(version.kernels, version.steps);
  return runs;
}

}  // namespace sandphys::bench
