#include "bench_options.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

namespace sandphys::bench {

namespace {

constexpr const char* kProgram = "sandphys-bench";

// A usage error: the message names the flag and the offending value.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Defaults of the paper's benchmark sizes (4K, 16K, 64K, 256K granules), also the box pile's.
const std::vector<std::string> kDefaultSizes = {"4K", "16K", "64K", "256K"};
constexpr std::uint32_t kDefaultSteps = 200;
// The box pile times 2000 substeps, as DEM codes time it: 0.1 s simulated at its fixed 5e-5 s.
constexpr std::uint32_t kDefaultBoxSteps = 2000;

// Substeps of settling by default. A crystal is static from the start: a short settle lets the
// column take up its elastic load. A lattice has to fall and compact: about 0.13 s simulated for
// the small piles, less for the large ones, whose settling would otherwise take most of the run
// on a CPU (llvmpipe); neither is enough to come to rest (the output says how far it got).
std::uint32_t defaultSettleSteps(std::uint32_t granules, Packing packing) {
  if (packing == Packing::Crystal) return 200;
  if (granules <= 16384) return 2000;
  if (granules <= 65536) return 1000;
  return 400;
}

// Wall-time caps per size by default, s: a full default run stays within about half an hour on
// a two-core machine running llvmpipe, even when it is shared.
constexpr double kDefaultBudgetSeconds = 300.0;

// "4096", "16K" or "1M" (K = 1024, M = 1024²) as a positive count.
std::uint32_t parseCount(const std::string& flag, const std::string& text, bool allowZero) {
  std::uint64_t value = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(first, last, value);
  std::uint64_t scale = 1;
  if (end != last && end + 1 == last) {
    if (*end == 'k' || *end == 'K') scale = 1024;
    if (*end == 'm' || *end == 'M') scale = 1024 * 1024;
  }
  if (ec != std::errc() || end == first || (end != last && (scale == 1 || end + 1 != last))) {
    throw UsageError(flag + " " + text + ": expected a whole number (K and M suffixes allowed)");
  }
  value *= scale;
  if (value > 0xffffffffu || (value == 0 && !allowZero)) {
    throw UsageError(flag + " " + text + ": must be in [" + (allowZero ? "0" : "1") +
                     ", 4294967295]");
  }
  return static_cast<std::uint32_t>(value);
}

// One value for every size, or one per size.
std::vector<std::uint32_t> perSize(const std::string& flag, const std::vector<std::string>& texts,
                                   std::size_t sizes, bool allowZero) {
  if (texts.size() != 1 && texts.size() != sizes) {
    throw UsageError(flag + ": give one value or one per size (" + std::to_string(sizes) +
                     "), not " + std::to_string(texts.size()));
  }
  std::vector<std::uint32_t> values;
  for (std::size_t i = 0; i < sizes; ++i) {
    values.push_back(parseCount(flag, texts[texts.size() == 1 ? 0 : i], allowZero));
  }
  return values;
}

// Fails now, before any simulation, if `path` cannot be written. A file that did not exist is
// removed again.
void checkWritable(const std::string& flag, const std::string& path) {
  errno = 0;
  const bool existed = std::ifstream(path).good();
  {
    std::ofstream probe(path, std::ios::app);
    if (!probe) {
      const std::string reason = errno ? std::strerror(errno) : "cannot open";
      throw UsageError(flag + ": cannot write '" + path + "': " + reason);
    }
  }
  if (!existed) std::remove(path.c_str());
}

std::string formatValue(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

std::optional<int> parseCommandLine(int argc, char** argv, BenchOptions& options) {
  CLI::App app{
      "sandphys benchmark at several granule counts, on one of two scenes (--scene):\n"
      "  cylinder (default): the settled cylinder pile of Longmore et al. 2013 (wall radius "
      "50 d, rough particle floor, smooth wall), d = 0.02 m; built directly (--packing).\n"
      "  box: the standard box pile: a square box of flat walls with friction, side "
      "36 d * sqrt(N/4096) so that the settled pile is about 15 d high, d = 0.01 m, 2500 kg/m^3, "
      "E = 1e7 Pa, nu = 0.3, e = 0.5, mu = 0.5 on every contact (grains, walls, floor), fixed "
      "dt = 5e-5 s, settled from a loose random lattice; 2000 substeps timed.\n"
      "Per size: granule-steps and particle-steps per wall second (the Cundall number is the "
      "first), contacts per particle, microseconds per particle-contact, dispatches per "
      "substep, neighbour-list builds per 1000 substeps, GPU memory per granule, simulated "
      "seconds per wall second and GPU time per kernel. The pile settles for --settle-steps "
      "substeps before --steps substeps are timed; the output states how settled it is "
      "(kinetic energy, contacts per granule, pile top, largest overlap).",
      kProgram};
  std::vector<std::string> sizes = kDefaultSizes;
  std::vector<std::string> steps;
  std::vector<std::string> settleSteps;
  std::string scene = "cylinder";
  MeasureOptions& measure = options.measure;
  measure.budgetSeconds = kDefaultBudgetSeconds;
  measure.settleBudgetSeconds = kDefaultBudgetSeconds;
  bool noKernelTimes = false;
  std::string packing = std::string(packingName(measure.pile.packing));
  // The lattice options serve the cylinder's lattice packing and the box alike.
  float spacing = measure.pile.spacing;
  float jitter = measure.pile.jitter;
  std::uint64_t seed = measure.pile.seed;
  bool quiet = false;
  std::vector<int> renderSize;

  app.add_option("--scene", scene,
                 "benchmark scene: 'cylinder' (the paper's pile, the default) or 'box' (the "
                 "standard box pile)")
      ->check(CLI::IsMember({"cylinder", "box"}))
      ->capture_default_str();
  app.add_option("--sizes", sizes, "granule counts, comma-separated (K = 1024)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--steps", steps,
                 "substeps timed per size: one value, or one per size (default: cylinder " +
                     std::to_string(kDefaultSteps) + ", box " + std::to_string(kDefaultBoxSteps) +
                     ")")
      ->delimiter(',');
  app.add_option("--settle-steps", settleSteps,
                 "substeps the pile settles before timing: one value, or one per size "
                 "(default: cylinder crystal 200; cylinder lattice 2000 up to 16K granules, 1000 "
                 "up to 64K, 400 above; box 1.5 free-fall times of the initial column's top onto "
                 "the floor, about 8,400-8,900 substeps = 0.42-0.44 s)")
      ->delimiter(',');
  app.add_option("--budget-seconds", measure.budgetSeconds,
                 "wall-time cap of the timed substeps per size, s (0 = none; checked every "
                 "--chunk substeps)")
      ->capture_default_str();
  app.add_option("--settle-budget-seconds", measure.settleBudgetSeconds,
                 "wall-time cap of the settling per size, s (0 = none)")
      ->capture_default_str();
  app.add_option("--chunk", measure.chunk,
                 "substeps per World::substep call (per World::step frame with --frames)")
      ->capture_default_str();
  app.add_flag("--frames", measure.frames,
               "time the substeps as a game runs them: World::step frames of --chunk substeps, "
               "the statistics read after each (WorldSettings::statsEachFrame), so that frames of "
               "sleeping sand skip their idle substeps (StepReport::idleSubsteps)");
  app.add_option("--pile-cache", measure.pileCache,
                 "folder of settled piles: a size whose pile an earlier run settled with the same "
                 "scene options, granules and settle substeps (and sleep) is restored from there "
                 "instead of settled again, bit for bit the same; a pile settled now is kept "
                 "there (not one whose settling ran out of budget)");
  app.add_option("--reserve-particles", measure.reserveParticles,
                 "particles every World reserves (and a quarter as many bodies), for what spare "
                 "capacity costs; 0: what the pile needs")
      ->check(CLI::Range(0u, 1u << 28))
      ->capture_default_str();
  app.add_option("--list-skin", measure.listSkin,
                 "skin of the neighbour lists, particle diameters (0: derived from the speed "
                 "guard, WorldSettings::listSkin); it changes the cost, not the result")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  app.add_option("--sort-interval", measure.sortInterval,
                 "substeps between sorts of the granules by place (WorldSettings::sortInterval: 0 "
                 "derives it, kNeverSortGranules never sorts)");
  app.add_flag("--shuffle", measure.shuffled,
               "the pile's granules added in a random order, the same poses: sand whose order in "
               "memory no longer follows place");
  app.add_option("--lammps-ranks", measure.lammpsRanks,
                 "after each size, run the same pile in LAMMPS for as many steps (exported at the "
                 "start of timing: fix rigid/small, pair granular), once per number of MPI ranks "
                 "given (1: lmp alone; comma-separated), and report its time beside sandphys's; "
                 "needs lmp and mpirun (lammps, openmpi-bin)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1024));
  app.add_option("--lammps-rounds", measure.lammpsRounds,
                 "with --lammps-ranks: time the substeps in this many rounds of equal length, "
                 "each followed by the LAMMPS runs of as many steps, so that the two alternate "
                 "on the machine; the table adds the median of the rounds' ratios (--steps must "
                 "be a multiple)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  app.add_option("--lammps-dir", measure.lammpsDir,
                 "with --lammps-ranks: folder of the decks and LAMMPS's output, one per size "
                 "(kept)")
      ->capture_default_str();
  app.add_option(
         "--compare-shaders", measure.compareShaders,
         "after each size's timed substeps, run the pile as timing started under each of "
         "these kernel versions (shader folders as SANDPHYS_SHADER_DIR takes them, or "
         "built-in: the library's own; comma-separated; FOLDER:sorted: that World sorts its "
         "granules by place in its first substep), one World each, in one process, "
         "--compare-rounds rounds of --steps / --compare-rounds substeps each in turn; "
         "reports each version's ms per substep and whether its state stayed bit for bit "
         "the first's")
      ->delimiter(',');
  app.add_option("--compare-rounds", measure.compareRounds,
                 "with --compare-shaders: rounds of each version")
      ->check(CLI::Range(1u, 10000u))
      ->capture_default_str();
  app.add_flag("--sleep", measure.sleep,
               "sleeping sand (WorldSettings::sleep): time the pile once it has fallen asleep");
  CLI::Option* rollingOption =
      app.add_option("--rolling-friction", measure.box.material.rollingFriction,
                     "box: rolling friction mu_r of every contact (Material::rollingFriction; "
                     "0: none, the standard pile), the settling included")
          ->check(CLI::Range(0.0f, 10.0f))
          ->capture_default_str();
  app.add_option("--rock", measure.rockSpeed,
                 "box: at the start of timing, set a ball of radius 3 d down on the pile near one "
                 "wall, rolling across it at this speed, m/s (0: no ball)")
      ->check(CLI::Range(0.0f, 10.0f))
      ->capture_default_str();
  CLI::Option* sandboxOption =
      app.add_option("--sandbox", measure.sandboxSeconds,
                     "box: instead of the timed substeps, run this many simulated seconds of a "
                     "sandbox script on the settled pile (a ball of radius 3 d dropped at the "
                     "start; a kinematic ball of radius 6 d sinks in at 1 s, ploughs 0.4 m/s for "
                     "1 s and is lifted out), timing every frame of 1/60 s")
          ->check(CLI::Range(0.0, 600.0))
          ->capture_default_str();
  CLI::Option* packingOption = app.add_option(
      "--packing", packing,
      "cylinder: initial pile: 'crystal' (aligned granules whose particles form an FCC packing "
      "on the floor, pressed by their weight: nearly static at once, denser and more "
      "ordered than a poured pile) or 'lattice' (random orientations 2.25 d apart: "
      "loose, the column still has to fall and compact, which takes far longer than "
      "a benchmark can wait); the box always starts from a lattice");
  packingOption->check(CLI::IsMember({"lattice", "crystal"}))->capture_default_str();
  std::string law = "hertz-mindlin";
  app.add_option("--contact-law", law,
                 "hertz-mindlin (the default) or paper (the law of Longmore et al. 2013)")
      ->check(CLI::IsMember({"hertz-mindlin", "paper"}))
      ->capture_default_str();
  CLI::Option* radiusOption =
      app.add_option("--cylinder-radius", measure.pile.cylinderRadius,
                     "cylinder: radius of the wall and the rough floor, d (the paper: 50)")
          ->capture_default_str();
  CLI::Option* heightOption =
      app.add_option("--cylinder-height", measure.pile.cylinderHeight,
                     "cylinder: height of the wall, d (the paper: 100); raised when the initial "
                     "pile is taller")
          ->capture_default_str();
  app.add_option("--spacing", spacing,
                 "lattice packing and box: spacing, d; spacing*(1-2*jitter) >= 2.225")
      ->capture_default_str();
  app.add_option("--jitter", jitter,
                 "lattice packing and box: random offset per axis, units of spacing")
      ->capture_default_str();
  app.add_option("--seed", seed, "lattice packing and box: seed of the jitter and orientations")
      ->capture_default_str();
  app.add_flag("--no-kernel-times", noKernelTimes,
               "do not profile the kernels after the timed substeps");
  app.add_option("--kernel-steps", measure.kernelSteps,
                 "substeps profiled with per-kernel GL timer queries after the timed ones (which "
                 "run without them)")
      ->capture_default_str();
  app.add_option("--render", renderSize,
                 "also time the renderer's passes (shadow, scene, composite) on each measured "
                 "pile at WIDTH HEIGHT px, once per quality preset (low, medium, high)")
      ->expected(2);
  app.add_option("--render-frames", measure.render.frames,
                 "frames timed per quality preset with --render")
      ->capture_default_str();
  app.add_option("--json", options.jsonPath, "write the results to this JSON file");
  app.add_flag("--quiet", quiet, "no progress lines on stderr");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(error);  // --help
    }
    std::cerr << kProgram << ": error: " << error.what() << "\nRun with --help for usage.\n";
    return kExitUsage;
  }

  try {
    measure.scene = scene == "box" ? BenchScene::Box : BenchScene::Cylinder;
    const bool box = measure.scene == BenchScene::Box;
    if (box) {
      for (const CLI::Option* option : {packingOption, radiusOption, heightOption}) {
        if (option->count() > 0) {
          throw UsageError(option->get_name() + ": applies to --scene cylinder only");
        }
      }
    }
    for (const CLI::Option* option : {sandboxOption, rollingOption}) {
      if (option->count() > 0 && !box) {
        throw UsageError(option->get_name() + ": applies to --scene box only");
      }
    }
    if (measure.sandboxSeconds > 0.0 && measure.rockSpeed > 0.0f) {
      throw UsageError("--sandbox with --rock: the sandbox script drops its own ball");
    }
    if (measure.frames && (measure.sandboxSeconds > 0.0 || !measure.compareShaders.empty())) {
      throw UsageError(
          "--frames with --sandbox or --compare-shaders: those run their own frames "
          "or rounds of substeps");
    }
    measure.pile.packing = packing == "crystal" ? Packing::Crystal : Packing::Lattice;
    measure.pile.contactLaw = *scenes::contactLawFromName(law);
    measure.box.contactLaw = measure.pile.contactLaw;
    measure.pile.spacing = measure.box.spacing = spacing;
    measure.pile.jitter = measure.box.jitter = jitter;
    measure.pile.seed = measure.box.seed = seed;
    if (sizes.empty()) throw UsageError("--sizes: give at least one granule count");
    std::vector<std::uint32_t> granules;
    for (const std::string& size : sizes) granules.push_back(parseCount("--sizes", size, false));
    if (steps.empty()) steps = {std::to_string(box ? kDefaultBoxSteps : kDefaultSteps)};
    const std::vector<std::uint32_t> timed = perSize("--steps", steps, granules.size(), false);
    std::vector<std::uint32_t> settle;
    if (settleSteps.empty()) {
      for (std::uint32_t n : granules) {
        if (box) {
          BoxPileConfig config = measure.box;
          config.granules = n;
          try {
            settle.push_back(boxPileSettleSteps(config));
          } catch (const Error& error) {
            throw UsageError("--sizes " + std::to_string(n) + ": " + error.what());
          }
        } else {
          settle.push_back(defaultSettleSteps(n, measure.pile.packing));
        }
      }
    } else {
      settle = perSize("--settle-steps", settleSteps, granules.size(), true);
    }
    for (std::size_t i = 0; i < granules.size(); ++i) {
      options.sizes.push_back({granules[i], settle[i], timed[i]});
      if (!measure.lammpsRanks.empty() && timed[i] % measure.lammpsRounds != 0) {
        throw UsageError("--steps " + std::to_string(timed[i]) + " with --lammps-rounds " +
                         std::to_string(measure.lammpsRounds) +
                         ": the rounds must be of equal length (a multiple of the rounds)");
      }
    }
    if (!(measure.budgetSeconds >= 0.0)) {
      throw UsageError("--budget-seconds " + formatValue(measure.budgetSeconds) + ": must be >= 0");
    }
    if (!(measure.settleBudgetSeconds >= 0.0)) {
      throw UsageError("--settle-budget-seconds " + formatValue(measure.settleBudgetSeconds) +
                       ": must be >= 0");
    }
    if (measure.chunk == 0) throw UsageError("--chunk 0: must be >= 1");
    if (!(measure.pile.cylinderRadius >= 2.0f && measure.pile.cylinderRadius <= 1.0e4f)) {
      throw UsageError("--cylinder-radius " + formatValue(measure.pile.cylinderRadius) +
                       ": must be in [2, 10000] d");
    }
    if (!(measure.pile.cylinderHeight >= 1.0f && measure.pile.cylinderHeight <= 1.0e5f)) {
      throw UsageError("--cylinder-height " + formatValue(measure.pile.cylinderHeight) +
                       ": must be in [1, 100000] d");
    }
    if (!(measure.pile.jitter >= 0.0f && measure.pile.jitter <= 0.25f)) {
      throw UsageError("--jitter " + formatValue(measure.pile.jitter) + ": must be in [0, 0.25]");
    }
    // GranuleBlock's own limit, checked here so that the message names the flags.
    if (!(measure.pile.spacing * (1.0f - 2.0f * measure.pile.jitter) >= 2.225f)) {
      throw UsageError("--spacing " + formatValue(measure.pile.spacing) + " with --jitter " +
                       formatValue(measure.pile.jitter) +
                       ": spacing*(1-2*jitter) must be >= 2.225 d, or granules start overlapping");
    }
    if (!renderSize.empty()) {
      for (const int side : renderSize) {
        if (side < 16 || side > 16384) {
          throw UsageError("--render " + std::to_string(renderSize[0]) + " " +
                           std::to_string(renderSize[1]) + ": each side must be in [16, 16384] px");
        }
      }
      measure.render.width = renderSize[0];
      measure.render.height = renderSize[1];
    }
    if (measure.render.frames == 0) throw UsageError("--render-frames 0: must be >= 1");
    if (measure.kernelSteps == 0) throw UsageError("--kernel-steps 0: must be >= 1");
    if (!measure.lammpsRanks.empty() && measure.sandboxSeconds > 0.0) {
      throw UsageError("--lammps-ranks with --sandbox: LAMMPS runs timed substeps, not the script");
    }
    for (const std::string& version : measure.compareShaders) {
      const std::string folder = versionFolder(version);
      std::error_code error;
      if (folder != kBuiltInShaders && !std::filesystem::is_directory(folder, error)) {
        throw UsageError("--compare-shaders " + version + ": not a folder (a shader folder as " +
                         "SANDPHYS_SHADER_DIR takes it, or " + kBuiltInShaders + ", either " +
                         "optionally followed by " + std::string(kSortedSuffix) + ")");
      }
    }
    if (!measure.compareShaders.empty() &&
        (measure.rockSpeed > 0.0f || measure.sandboxSeconds > 0.0)) {
      throw UsageError(
          "--compare-shaders with --rock or --sandbox: the versions run the settled "
          "pile as it was built, without the ball or the script's bodies");
    }
    measure.kernelTimes = !noKernelTimes;
    measure.progress = !quiet;
    if (!options.jsonPath.empty()) checkWritable("--json", options.jsonPath);
  } catch (const UsageError& error) {
    std::cerr << kProgram << ": error: " << error.what() << "\nRun with --help for usage.\n";
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace sandphys::bench
