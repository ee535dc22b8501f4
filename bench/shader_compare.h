#pragma once

// --compare-shaders: the settled pile run under several versions of the kernels in one process,
// a round of each in turn, so that the host's drift between minutes falls on every version alike
// (bench/README.md, "Comparing kernel versions").
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <sandphys/sandphys.h>

#include "bench_pile.h"
#include "kernel_times.h"

namespace sandphys::bench {

/// The folder name that stands for the kernels built into the library (no SANDPHYS_SHADER_DIR).
inline constexpr const char* kBuiltInShaders = "built-in";
/// After a version's folder: that World sorts its granules by place in its first substep
/// (WorldSettings::sortInterval), so that the versions may differ in the order of the granules
/// rather than in the kernels; a version without it never sorts.
inline constexpr std::string_view kSortedSuffix = ":sorted";

/// A version's folder without kSortedSuffix, and whether it had it.
std::string versionFolder(const std::string& version, bool* sorted = nullptr);

/// One version's runs.
struct ShaderRun {
  std::string folder;  ///< a shader folder (SANDPHYS_SHADER_DIR), or kBuiltInShaders
  /// Wall time per substep of each round, ms, each ending with a sync.
  std::vector<double> roundMilliseconds;
  double cpuSeconds = 0.0;      ///< process CPU time over its rounds (all threads), s
  std::uint32_t steps = 0;      ///< substeps over its rounds
  std::uint64_t stateHash = 0;  ///< World::readStateHash after its last round
  /// ShaderComparePlan::kernelTimes: each kernel's GPU time per substep over its rounds.
  std::vector<KernelStep> kernels;

  double medianMilliseconds() const;
  double fastestMilliseconds() const;
  double cpuMillisecondsPerStep() const;
};

/// How the versions are run: `rounds` rounds of `stepsPerRound` substeps each, in calls of
/// `chunk`, after `warmupSteps` untimed ones (llvmpipe compiles a kernel at its first dispatch);
/// with `kernelTimes`, every World's timer queries on throughout (each pays for them alike), so
/// that a change to one pass shows in its own time as well.
struct ShaderComparePlan {
  std::vector<std::string> folders;
  std::uint32_t rounds = 10;
  std::uint32_t stepsPerRound = 200;
  std::uint32_t chunk = 10;
  std::uint32_t warmupSteps = 10;
  bool kernelTimes = false;
};

/// Builds `pile` in one World of `settings` per folder, restores `start` into each and runs them
/// in turn, the order reversed every other round. Throws sandphys::Error (a kernel that does not
/// compile names its file and line), with the folder named.
std::vector<ShaderRun> compareShaders(const GpuContext& gpu, const WorldSettings& settings,
                                      const BenchPile& pile, const WorldSnapshot& start,
                                      const ShaderComparePlan& plan);

}  // namespace sandphys::bench
