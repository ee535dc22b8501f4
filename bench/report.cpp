#include "report.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <fstream>

#include <sandphys/error.h>

#include "timing.h"

namespace sandphys::bench {

namespace {

// A float as the shortest decimal that reads back to it (0.02f -> 0.02, not 0.0199999996).
double shortest(float value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer - 1, value);
  if (ec != std::errc()) return value;
  *end = '\0';
  return std::strtod(buffer, nullptr);
}

// `bytes` of GPU memory per granule of `size` (0 without granules).
double perGranule(const SizeResult& size, std::uint64_t bytes) {
  return size.granules > 0 ? double(bytes) / size.granules : 0.0;
}

// Bytes per granule of each buffer, by name.
nlohmann::json memoryJson(const SizeResult& size) {
  nlohmann::json out = nlohmann::json::object();
  for (const BufferMemory& buffer : size.gpuMemoryByBuffer) {
    out[buffer.name] = perGranule(size, buffer.bytes);
  }
  return out;
}

// Bytes per granule of the buffer `name` in `size` (0 when it has none).
double bytesPerGranule(const SizeResult& size, const std::string& name) {
  for (const BufferMemory& buffer : size.gpuMemoryByBuffer) {
    if (buffer.name == name) return perGranule(size, buffer.bytes);
  }
  return 0.0;
}

// GPU memory per granule, buffer by buffer: the buffers that hold 0.5% or more of the first size's
// memory, the largest first, then the others together.
void printMemory(std::FILE* out, const BenchReport& report) {
  const SizeResult& first = report.sizes.front();
  std::vector<BufferMemory> large;
  for (const BufferMemory& buffer : first.gpuMemoryByBuffer) {
    if (200 * buffer.bytes >= first.gpuMemoryBytes) large.push_back(buffer);
  }
  std::stable_sort(large.begin(), large.end(),
                   [](const BufferMemory& a, const BufferMemory& b) { return a.bytes > b.bytes; });
  std::fprintf(out,
               "\nGPU memory per granule, B, by buffer (World::gpuMemoryByBuffer: those with 0.5%% "
               "or more of the first size's, the largest first):\n%-20s",
               "buffer");
  for (const SizeResult& s : report.sizes) std::fprintf(out, " %10u", s.granules);
  std::fprintf(out, "\n");
  for (const BufferMemory& buffer : large) {
    std::fprintf(out, "%-20s", buffer.name.c_str());
    for (const SizeResult& s : report.sizes) {
      std::fprintf(out, " %10.1f", bytesPerGranule(s, buffer.name));
    }
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "%-20s", "the others");
  for (const SizeResult& s : report.sizes) {
    double rest = perGranule(s, s.gpuMemoryBytes);
    for (const BufferMemory& buffer : large) rest -= bytesPerGranule(s, buffer.name);
    std::fprintf(out, " %10.1f", rest);
  }
  std::fprintf(out, "\n%-20s", "all");
  for (const SizeResult& s : report.sizes) {
    std::fprintf(out, " %10.1f", perGranule(s, s.gpuMemoryBytes));
  }
  std::fprintf(out, "\n");
}

// Kernel names over all sizes, in dispatch order (the order of first appearance).
std::vector<std::string> kernelNames(const BenchReport& report) {
  std::vector<std::string> names;
  for (const SizeResult& size : report.sizes) {
    for (const KernelStep& kernel : size.kernels) {
      if (std::find(names.begin(), names.end(), kernel.name) == names.end()) {
        names.push_back(kernel.name);
      }
    }
  }
  return names;
}

const KernelStep* findKernel(const std::vector<KernelStep>& kernels, const std::string& name) {
  for (const KernelStep& kernel : kernels) {
    if (kernel.name == name) return &kernel;
  }
  return nullptr;
}

nlohmann::json pileStateJson(const PileState& state) {
  return {
      {"simulated_seconds", state.simulatedSeconds},
      {"contacts", state.contacts},
      {"contacts_per_granule", state.contactsPerGranule},
      {"kinetic_energy_per_granule_j", state.kineticEnergyPerGranule},
      {"rms_speed_m_per_s", state.rmsSpeed},
      {"max_overlap_d", state.maxOverlap},
      {"pile_top_d", state.pileTop},
      {"granules_outside", state.granulesOutside},
  };
}

nlohmann::json renderJson(const RenderTiming& timing) {
  return {
      {"quality", timing.quality},
      {"render_width", timing.renderWidth},
      {"render_height", timing.renderHeight},
      {"shadow_map_size", timing.shadowMapSize},
      {"ao_samples", timing.aoSamples},
      {"shadow_ms", timing.shadowMs},
      {"scene_ms", timing.sceneMs},
      {"composite_ms", timing.compositeMs},
      {"gpu_ms", timing.totalMs},
      {"wall_ms", timing.wallMs},
  };
}

// The sandbox frames in spans of 0.25 s simulated: mean wall ms per frame, the counts at the
// span's last frame.
void printTimeline(std::FILE* out, const SizeResult& size) {
  std::fprintf(out, "  %u granules, sandbox script (frames of 1/60 s):\n", size.granules);
  std::fprintf(out, "    %-12s %10s %10s %14s\n", "simulated s", "awake", "asleep", "ms per frame");
  constexpr double kSpan = 0.25;
  double sum = 0.0;
  int frames = 0;
  double spanEnd = kSpan;
  for (std::size_t i = 0; i < size.timeline.size(); ++i) {
    const TimelineFrame& f = size.timeline[i];
    sum += f.wallMilliseconds;
    ++frames;
    const bool last = i + 1 == size.timeline.size();
    if (f.simulatedSeconds + 1e-9 >= spanEnd || last) {
      std::fprintf(out, "    %-12.2f %10u %10u %14.1f\n", f.simulatedSeconds, f.granulesAwake,
                   f.granulesAsleep, sum / frames);
      sum = 0.0;
      frames = 0;
      spanEnd += kSpan;
    }
  }
}

// Each kernel's GPU ms per substep, by name.
nlohmann::json kernelsJson(const std::vector<KernelStep>& kernels) {
  nlohmann::json out = nlohmann::json::object();
  for (const KernelStep& kernel : kernels) out[kernel.name] = kernel.millisecondsPerStep;
  return out;
}

nlohmann::json sizeJson(const SizeResult& size, double d) {
  nlohmann::json renders = nlohmann::json::array();
  for (const RenderTiming& timing : size.renders) renders.push_back(renderJson(timing));
  nlohmann::json kernels = nlohmann::json::object();
  for (const KernelStep& kernel : size.kernels) {
    kernels[kernel.name] = {
        {"ms_per_step", kernel.millisecondsPerStep},
        {"dispatches_per_step", kernel.dispatchesPerStep},
        {"share_of_kernel_time", size.kernelMillisecondsPerStep() > 0.0
                                     ? kernel.millisecondsPerStep / size.kernelMillisecondsPerStep()
                                     : 0.0}};
  }
  // Without kernel times there is nothing to count dispatches with: null, not a guess.
  const bool profiled = !size.kernels.empty();
  nlohmann::json layout = {{"spacing_d", size.layout.spacing / d},
                           {"columns", size.layout.columns},
                           {"full_layers", size.layout.fullLayers},
                           {"top_layer_granules", size.layout.topLayerGranules},
                           {"column_top_d", size.layout.columnTop / d},
                           {"wall_height_d", size.layout.wallHeight},
                           {"wall_raised", size.layout.wallRaised}};
  if (size.layout.boxSide > 0.0f) layout["box_side_d"] = size.layout.boxSide;
  // [simulated s, wall ms, granules awake, granules asleep] per frame.
  nlohmann::json timeline = nlohmann::json::array();
  for (const TimelineFrame& f : size.timeline) {
    timeline.push_back({f.simulatedSeconds, f.wallMilliseconds, f.granulesAwake, f.granulesAsleep});
  }
  nlohmann::json result = {
      {"granules", size.granules},
      {"particles", size.particles},
      {"floor_particles", size.floorParticles},
      {"particle_capacity", size.particleCapacity},
      {"contacts", size.measured.contacts},
      {"contacts_per_granule", size.measured.contactsPerGranule},
      {"cundall_number", size.cundallNumber()},
      {"granule_steps_per_second", size.cundallNumber()},
      {"particle_steps_per_second", size.particleStepsPerSecond()},
      {"contacts_per_particle", size.contactsPerParticle()},
      {"microseconds_per_particle_contact",
       size.measured.contacts > 0 ? nlohmann::json(size.microsecondsPerParticleContact())
                                  : nlohmann::json(nullptr)},
      {"dispatches_per_substep",
       profiled ? nlohmann::json(size.dispatchesPerStep()) : nlohmann::json(nullptr)},
      {"list_builds_per_1000_substeps", size.listBuildsPer1000Steps()},
      {"list_overflows", size.listOverflows},
      {"list_skin_d", size.listSkin / d},
      {"list_near_skin_d", size.listNearSkin / d},
      {"list_near_markings", size.listNearMarkings},
      {"sleep_wait_substeps", size.sleepWaitSteps},
      {"granules_asleep_at_start", size.asleepAtStart},
      {"granules_asleep_at_end", size.asleepAtEnd},
      {"idle_substeps", size.idleSubsteps},
      {"idle_frames", size.idleFrameMs.size()},
      {"idle_frame_ms_median", median(size.idleFrameMs)},
      {"still_grid_builds", size.stillGridBuilds},
      {"moving_grid_particles", size.movingGridParticles},
      {"rock_particles", size.rockParticles},
      {"microseconds_per_granule_step", size.microsecondsPerGranuleStep()},
      {"simulated_seconds_per_wall_second", size.simulatedPerWallSecond()},
      {"gpu_memory_bytes", size.gpuMemoryBytes},
      {"gpu_memory_bytes_per_granule", perGranule(size, size.gpuMemoryBytes)},
      {"gpu_memory_bytes_per_granule_by_buffer", memoryJson(size)},
      {"time_step_s", shortest(size.timeStep)},
      {"contact_time_s", shortest(size.contactTime)},
      {"steps", size.steps},
      {"steps_planned", size.plan.steps},
      {"budget_hit", size.budgetHit},
      {"wall_seconds", size.wallSeconds},
      {"round_wall_seconds", size.roundWallSeconds},
      {"wall_ms_per_step", size.wallMillisecondsPerStep()},
      {"cpu_ms_per_step", size.cpuMillisecondsPerStep()},
      {"kernel_ms_per_step", kernels},
      {"kernel_sum_ms_per_step", size.kernelMillisecondsPerStep()},
      {"render", renders},
      {"cpu_seconds", size.cpuSeconds},
      {"cpu_utilisation", size.wallSeconds > 0.0 ? size.cpuSeconds / size.wallSeconds : 0.0},
      {"load_average_before", size.loadBefore},
      {"load_average_after", size.loadAfter},
      {"penetration_clamps", size.penetrationClamps},
      {"contact_slot_overflows", size.contactSlotOverflows},
      {"velocity_clamps", size.velocityClamps},
      {"setup_seconds", size.setupSeconds},
      {"layout", layout},
      {"settle",
       {{"steps", size.settleSteps},
        {"steps_planned", size.plan.settleSteps},
        {"simulated_seconds", size.settled.simulatedSeconds},
        {"wall_seconds", size.settleWallSeconds},
        {"budget_hit", size.settleBudgetHit},
        {"restored_from", size.settledFrom},
        {"restored_settle_wall_seconds", size.settledFromWallSeconds}}},
      {"state",
       {{"built", pileStateJson(size.built)},
        {"settled", pileStateJson(size.settled)},
        {"measured", pileStateJson(size.measured)}}},
  };
  if (!size.timeline.empty()) result["sandbox_timeline"] = timeline;
  nlohmann::json lammps = nlohmann::json::array();
  for (const LammpsTiming& run : size.lammps) {
    const bool ran = run.failure.empty();
    lammps.push_back(
        {{"ranks", run.ranks},
         {"deck", run.deck},
         {"loop_seconds", run.loopSeconds},
         {"steps", run.steps},
         {"ms_per_step", ran ? nlohmann::json(run.millisecondsPerStep()) : nlohmann::json(nullptr)},
         {"granule_steps_per_second",
          ran ? nlohmann::json(run.granuleStepsPerSecond(size.granules)) : nlohmann::json(nullptr)},
         // Above 1: sandphys runs faster than this LAMMPS run.
         {"sandphys_speed_ratio",
          ran ? nlohmann::json(size.speedAgainst(run)) : nlohmann::json(nullptr)},
         {"round_loop_seconds", run.roundLoopSeconds},
         {"sandphys_speed_ratio_median_of_rounds",
          ran ? nlohmann::json(size.medianRoundSpeedAgainst(run)) : nlohmann::json(nullptr)},
         {"failure", run.failure}});
  }
  if (!size.lammps.empty()) result["lammps"] = lammps;
  nlohmann::json versions = nlohmann::json::array();
  for (const ShaderRun& run : size.shaderRuns) {
    versions.push_back({{"folder", run.folder},
                        {"round_ms_per_step", run.roundMilliseconds},
                        {"median_ms_per_step", run.medianMilliseconds()},
                        {"fastest_ms_per_step", run.fastestMilliseconds()},
                        {"cpu_ms_per_step", run.cpuMillisecondsPerStep()},
                        {"steps", run.steps},
                        {"state_hash", hex(run.stateHash)},
                        {"kernel_ms_per_substep", kernelsJson(run.kernels)},
                        {"same_state_as_first", run.stateHash == size.shaderRuns[0].stateHash}});
  }
  if (!size.shaderRuns.empty()) result["shader_comparison"] = versions;
  return result;
}

}  // namespace

nlohmann::json pileJson(const MeasureOptions& measure) {
  nlohmann::json scene;
  if (measure.scene == BenchScene::Box) {
    const BoxPileConfig& box = measure.box;
    scene = {{"benchmark", "box-pile"},
             {"description",
              "standard box pile: tetrahedral granules in a closed square box of flat "
              "walls with friction, side 36 d * sqrt(N/4096) so that the settled pile is about "
              "15 d high; settled from a loose random lattice before timing"},
             {"options",
              {{"scene", benchSceneName(measure.scene)},
               {"contact_law", scenes::contactLawName(box.contactLaw)},
               {"particle_diameter_m", shortest(box.particleDiameter)},
               {"box_side_at_4096_d", shortest(box.sideAt4096)},
               {"density_kg_per_m3", shortest(box.material.density)},
               {"youngs_modulus_pa", shortest(box.material.youngsModulus)},
               {"poisson_ratio", shortest(box.material.poissonRatio)},
               {"restitution", shortest(box.material.restitution)},
               {"friction", shortest(box.material.friction)},
               {"wall_friction", shortest(box.wallMaterial.friction)},
               {"wall_restitution", shortest(box.wallMaterial.restitution)},
               {"time_step_s", shortest(box.timeStep)},
               {"spacing_d", shortest(box.spacing)},
               {"jitter", shortest(box.jitter)},
               {"seed", box.seed}}}};
    // Only when there is any, so that the keys of the piles settled without it stay.
    if (box.material.rollingFriction > 0.0f) {
      scene["options"]["rolling_friction"] = shortest(box.material.rollingFriction);
    }
  } else {
    scene = {{"benchmark", "cylinder-pile"},
             {"description",
              "settled cylinder pile of Longmore et al. 2013: smooth wall of radius 50 d, rough "
              "particle floor; built as a dense lattice from the floor up and settled before "
              "timing"},
             {"options",
              {{"scene", benchSceneName(measure.scene)},
               {"contact_law", scenes::contactLawName(measure.pile.contactLaw)},
               {"packing", packingName(measure.pile.packing)},
               {"particle_diameter_m", shortest(measure.pile.particleDiameter)},
               {"cylinder_radius_d", shortest(measure.pile.cylinderRadius)},
               {"cylinder_height_d", shortest(measure.pile.cylinderHeight)},
               {"spacing_d", shortest(measure.pile.spacing)},
               {"jitter", shortest(measure.pile.jitter)},
               {"seed", measure.pile.seed}}}};
  }
  return scene;
}

nlohmann::json reportJson(const BenchOptions& options, const BenchReport& report) {
  const MeasureOptions& measure = options.measure;
  nlohmann::json sizes = nlohmann::json::array();
  for (const SizeResult& size : report.sizes) {
    sizes.push_back(sizeJson(size, particleDiameter(measure)));
  }
  nlohmann::json scene = pileJson(measure);
  nlohmann::json& common = scene["options"];
  common["chunk"] = measure.chunk;
  common["frames"] = measure.frames;
  common["budget_seconds"] = measure.budgetSeconds;
  common["settle_budget_seconds"] = measure.settleBudgetSeconds;
  common["kernel_times"] = measure.kernelTimes;
  common["kernel_steps"] = measure.kernelSteps;
  return {
      {"benchmark", scene["benchmark"]},
      {"description", scene["description"]},
      {"gpu", report.gpu},
      {"hardware_threads", report.hardwareThreads},
      {"options", common},
      {"sizes", sizes},
  };
}

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

void writeJson(const std::string& path, const nlohmann::json& json) {
  std::ofstream file(path);
  file << json.dump(2) << '\n';
  if (!file) throw Error("--json: cannot write '" + path + "'");
}

void printReport(std::FILE* out, const BenchOptions& options, const BenchReport& report) {
  const MeasureOptions& measure = options.measure;
  const bool box = measure.scene == BenchScene::Box;
  const double d = particleDiameter(measure);
  const std::string law(scenes::contactLawName(measure.pile.contactLaw));
  if (box) {
    const BoxPileConfig& c = measure.box;
    std::fprintf(out,
                 "sandphys-bench: settled box pile (square box of flat walls with friction, side "
                 "%g d * sqrt(N/4096), from a loose random lattice), d = %g m, %g kg/m^3, E = %g "
                 "Pa, nu = %g, e = %g, mu = %g (grains), rolling mu_r = %g, walls and floor mu = "
                 "%g, e = %g, dt = %g s, %s\nGPU: %s (%u hardware threads)\n\n",
                 double(c.sideAt4096), d, double(c.material.density),
                 double(c.material.youngsModulus), double(c.material.poissonRatio),
                 double(c.material.restitution), double(c.material.friction),
                 double(c.material.rollingFriction), double(c.wallMaterial.friction),
                 double(c.wallMaterial.restitution), double(c.timeStep), law.c_str(),
                 report.gpu.c_str(), report.hardwareThreads);
  } else {
    std::fprintf(out,
                 "sandphys-bench: settled cylinder pile (wall radius %g d, rough particle floor, "
                 "smooth wall), d = %g m, %s packing, %s\nGPU: %s (%u hardware threads)\n\n",
                 double(measure.pile.cylinderRadius), d,
                 std::string(packingName(measure.pile.packing)).c_str(), law.c_str(),
                 report.gpu.c_str(), report.hardwareThreads);
  }

  std::fprintf(out, "%9s %10s %10s %9s %11s %12s %12s %9s %9s %9s\n", "granules", "particles",
               "capacity", "contacts", "Cundall", "us/gran-step", "sim s/wall s", "ms/step",
               "CPU ms", "B/gran");
  for (const SizeResult& s : report.sizes) {
    std::fprintf(out, "%9u %10u %10u %9u %11.4g %12.4g %12.4g %9.2f %9.2f %9.0f\n", s.granules,
                 s.particles, s.particleCapacity, s.measured.contacts, s.cundallNumber(),
                 s.microsecondsPerGranuleStep(), s.simulatedPerWallSecond(),
                 s.wallMillisecondsPerStep(), s.cpuMillisecondsPerStep(),
                 double(s.gpuMemoryBytes) / s.granules);
  }
  std::fprintf(out,
               "(ms/step: wall time per substep; CPU ms: process CPU time per substep over all "
               "threads, which on llvmpipe run the kernels; with the CPU utilisation in the notes "
               "it shows how much of a shared machine the run got)\n");

  std::fprintf(out, "\nPer particle, contact and dispatch:\n");
  std::fprintf(out, "%9s %10s %13s %13s %10s %12s %11s %14s %9s %12s\n", "granules", "particles",
               "granule-st/s", "particle-st/s", "contacts/p", "us/p-contact", "dispatches",
               "list builds/1k", "B/gran", "sim s/wall s");
  for (const SizeResult& s : report.sizes) {
    char perContact[24] = "n/a";  // no contacts, nothing to share the time among
    if (s.measured.contacts > 0) {
      std::snprintf(perContact, sizeof perContact, "%.4g", s.microsecondsPerParticleContact());
    }
    char dispatches[24] = "n/a";
    if (!s.kernels.empty())
      std::snprintf(dispatches, sizeof dispatches, "%.1f", s.dispatchesPerStep());
    char builds[24];
    std::snprintf(builds, sizeof builds, "%.1f", s.listBuildsPer1000Steps());
    std::fprintf(out, "%9u %10u %13.4g %13.4g %10.2f %12s %11s %14s %9.0f %12.4g\n", s.granules,
                 s.particles, s.cundallNumber(), s.particleStepsPerSecond(),
                 s.contactsPerParticle(), perContact, dispatches, builds,
                 double(s.gpuMemoryBytes) / s.granules, s.simulatedPerWallSecond());
  }
  std::fprintf(out,
               "(granule-st/s: granule-steps per wall second, the Cundall number; particle-st/s: "
               "particle-steps per wall second%s; contacts/p: contacts (particle pairs and "
               "collider contacts, World stats at the end of timing) per particle; us/p-contact: "
               "wall time per substep / contacts; dispatches: GL compute dispatches per substep, "
               "all kernels, the list build's indirect ones included (zero groups when no build "
               "is due); list builds/1k: neighbour-list builds per 1000 substeps "
               "(WorldStats::listBuilds); n/a: no contacts, or --no-kernel-times)\n",
               box ? "" : ", the rough floor's included");

  if (!measure.lammpsRanks.empty()) {
    std::fprintf(out,
                 "\nSide by side with LAMMPS (the pile as timing starts, exported by exportLammps: "
                 "fix rigid/small, pair granular Hertz-Mindlin, the same material and dt; as many "
                 "steps, run after sandphys's, in %u round(s)):\n",
                 measure.lammpsRounds);
    std::fprintf(out, "%9s %16s %7s %15s %13s %16s %16s\n", "granules", "sandphys ms/step", "ranks",
                 "LAMMPS ms/step", "granule-st/s", "sandphys/LAMMPS", "median of rounds");
    for (const SizeResult& s : report.sizes) {
      for (const LammpsTiming& run : s.lammps) {
        if (!run.failure.empty()) {
          std::fprintf(out, "%9u %16.3f %7d  did not run: %s\n", s.granules,
                       s.wallMillisecondsPerStep(), run.ranks, run.failure.c_str());
          continue;
        }
        std::fprintf(out, "%9u %16.3f %7d %15.3f %13.4g %16.2f %16.2f\n", s.granules,
                     s.wallMillisecondsPerStep(), run.ranks, run.millisecondsPerStep(),
                     run.granuleStepsPerSecond(s.granules), s.speedAgainst(run),
                     s.medianRoundSpeedAgainst(run));
      }
    }
    std::fprintf(out,
                 "(LAMMPS ms/step: its \"Loop time\" over its steps; sandphys/LAMMPS: how many "
                 "times faster sandphys ran, below 1 slower, over all steps; median of rounds: "
                 "the same ratio round by round (--lammps-rounds), its median; both on this "
                 "machine, one after the other)\n");
  }

  if (!measure.compareShaders.empty()) {
    std::fprintf(out,
                 "\nKernel versions in one process (--compare-shaders: the pile as timing started, "
                 "one World each, %u rounds in turn):\n",
                 measure.compareRounds);
    std::fprintf(out, "%9s %3s %14s %14s %10s %9s %6s  %s\n", "granules", "#", "median ms/step",
                 "fastest ms/st", "CPU ms/st", "vs first", "state", "kernels");
    for (const SizeResult& s : report.sizes) {
      for (std::size_t v = 0; v < s.shaderRuns.size(); ++v) {
        const ShaderRun& run = s.shaderRuns[v];
        const ShaderRun& first = s.shaderRuns.front();
        std::fprintf(out, "%9u %3zu %14.3f %14.3f %10.3f %9.3f %6s  %s\n", s.granules, v + 1,
                     run.medianMilliseconds(), run.fastestMilliseconds(),
                     run.cpuMillisecondsPerStep(),
                     run.medianMilliseconds() / first.medianMilliseconds(),
                     run.stateHash == first.stateHash ? "same" : "DIFFER", run.folder.c_str());
      }
    }
    std::fprintf(out,
                 "(ms/step: wall time per substep of a round, which ends with a sync; vs first: "
                 "the median against the first version's, below 1 faster; state: World's state "
                 "hash after the last round, bit for bit the first version's or not)\n");
    if (measure.kernelTimes) {
      std::fprintf(out,
                   "Their kernels (GPU ms per substep over the rounds, timer queries on in every "
                   "version; columns as # above):\n");
      for (const SizeResult& s : report.sizes) {
        if (s.shaderRuns.empty()) continue;
        std::fprintf(out, "%9s %-24s", "granules", "kernel");
        for (std::size_t v = 0; v < s.shaderRuns.size(); ++v) std::fprintf(out, " %9zu", v + 1);
        std::fprintf(out, "\n");
        for (const KernelStep& kernel : s.shaderRuns.front().kernels) {
          std::fprintf(out, "%9u %-24s", s.granules, kernel.name.c_str());
          for (const ShaderRun& run : s.shaderRuns) {
            if (const KernelStep* own = findKernel(run.kernels, kernel.name)) {
              std::fprintf(out, " %9.3f", own->millisecondsPerStep);
            } else {
              std::fprintf(out, " %9s", "-");
            }
          }
          std::fprintf(out, "\n");
        }
      }
    }
  }

  std::fprintf(out, "\nHow settled (at the start of timing -> at its end):\n");
  std::fprintf(out, "%9s %14s %20s %18s %16s %10s %14s\n", "granules", "settle steps",
               "KE/granule J", "contacts/granule", "pile top d", "overlap d", "timed steps");
  for (const SizeResult& s : report.sizes) {
    char settle[32];
    std::snprintf(settle, sizeof settle, "%u (%.0f ms)", s.settleSteps,
                  1e3 * s.settled.simulatedSeconds);
    char energy[48];
    std::snprintf(energy, sizeof energy, "%.2e->%.2e", s.settled.kineticEnergyPerGranule,
                  s.measured.kineticEnergyPerGranule);
    char contacts[48];
    std::snprintf(contacts, sizeof contacts, "%.2f->%.2f", s.settled.contactsPerGranule,
                  s.measured.contactsPerGranule);
    char top[64];
    std::snprintf(top, sizeof top, "%.1f->%.1f->%.1f", s.layout.columnTop / d, s.settled.pileTop,
                  s.measured.pileTop);
    char timed[32];
    std::snprintf(timed, sizeof timed, "%u%s", s.steps, s.budgetHit ? " (budget)" : "");
    std::fprintf(out, "%9u %14s %20s %18s %16s %10.3f %14s\n", s.granules, settle, energy, contacts,
                 top, s.measured.maxOverlap, timed);
  }
  std::fprintf(out,
               "(pile top: initial -> start of timing -> end of timing; overlap: largest "
               "particle overlap while timing%s)\n",
               options.measure.pile.contactLaw == ContactLaw::PaperViscous
                   ? "; the paper's law caps it at 0.1 d"
                   : "");

  const std::vector<std::string> names = kernelNames(report);
  if (!names.empty()) {
    std::fprintf(out,
                 "\nGPU time per substep, ms (GL timestamp queries over %u substeps after the "
                 "timed ones, which ran without them; wall: the timed substeps):\n%-20s",
                 measure.kernelSteps, "kernel");
    for (const SizeResult& s : report.sizes) std::fprintf(out, " %10u", s.granules);
    std::fprintf(out, "\n");
    for (const std::string& name : names) {
      std::fprintf(out, "%-20s", name.c_str());
      for (const SizeResult& s : report.sizes) {
        const KernelStep* kernel = findKernel(s.kernels, name);
        std::fprintf(out, " %10.3f", kernel ? kernel->millisecondsPerStep : 0.0);
      }
      std::fprintf(out, "\n");
    }
    std::fprintf(out, "%-20s", "sum of kernels");
    for (const SizeResult& s : report.sizes) {
      std::fprintf(out, " %10.3f", s.kernelMillisecondsPerStep());
    }
    std::fprintf(out, "\n%-20s", "wall per substep");
    for (const SizeResult& s : report.sizes) {
      std::fprintf(out, " %10.3f", s.wallMillisecondsPerStep());
    }
    std::fprintf(out, "\n");
  }

  if (!report.sizes.empty() && report.sizes.front().granules > 0) printMemory(out, report);

  if (measure.render.width > 0) {
    std::fprintf(out,
                 "\nRendering, ms per frame at %dx%d (GL timestamps per pass; wall: draw to "
                 "finished frame), beside the simulation's wall ms per substep:\n",
                 measure.render.width, measure.render.height);
    std::fprintf(out, "%10s %-7s %9s %6s %3s %8s %8s %9s %8s %8s %11s\n", "granules", "quality",
                 "lit at", "shadow", "AO", "shadow", "scene", "composite", "gpu", "wall",
                 "sim/substep");
    for (const SizeResult& s : report.sizes) {
      for (const RenderTiming& r : s.renders) {
        char litAt[24];
        std::snprintf(litAt, sizeof litAt, "%dx%d", r.renderWidth, r.renderHeight);
        std::fprintf(out, "%10u %-7s %9s %6d %3d %8.1f %8.1f %9.1f %8.1f %8.1f %11.1f\n",
                     s.granules, r.quality.c_str(), litAt, r.shadowMapSize, r.aoSamples, r.shadowMs,
                     r.sceneMs, r.compositeMs, r.totalMs, r.wallMs, s.wallMillisecondsPerStep());
      }
    }
  }

  std::fprintf(out, "\nNotes:\n");
  for (const SizeResult& s : report.sizes) {
    if (box) {
      std::fprintf(out,
                   "  %u granules: dt %.3g s = t_n / %.1f (the World refuses dt above t_n / "
                   "%g); box %.1f d x %.1f d x %.0f d high; %u columns x %u layers%s; CPU "
                   "utilisation %.2f cores; load average %.2f -> %.2f; setup %.1f s, settle %.1f "
                   "s wall%s\n",
                   s.granules, double(s.timeStep),
                   s.timeStep > 0.0f ? double(s.contactTime / s.timeStep) : 0.0,
                   double(kMinStepsPerContact), double(s.layout.boxSide), double(s.layout.boxSide),
                   double(s.layout.wallHeight), s.layout.columns, s.layout.fullLayers,
                   s.layout.topLayerGranules > 0 ? " + partial layer" : "",
                   s.wallSeconds > 0.0 ? s.cpuSeconds / s.wallSeconds : 0.0, s.loadBefore,
                   s.loadAfter, s.setupSeconds, s.settleWallSeconds,
                   s.settleBudgetHit ? " (settle budget hit)" : "");
      continue;
    }
    std::fprintf(
        out,
        "  %u granules: dt %.3g s; %u columns x %u layers%s; wall %.0f d%s; CPU "
        "utilisation %.2f cores; load average %.2f -> %.2f; setup %.1f s, settle %.1f s "
        "wall%s\n",
        s.granules, double(s.timeStep), s.layout.columns, s.layout.fullLayers,
        s.layout.topLayerGranules > 0 ? " + partial layer" : "", double(s.layout.wallHeight),
        s.layout.wallRaised ? " (raised from the paper's 100 d to hold the column)" : "",
        s.wallSeconds > 0.0 ? s.cpuSeconds / s.wallSeconds : 0.0, s.loadBefore, s.loadAfter,
        s.setupSeconds, s.settleWallSeconds, s.settleBudgetHit ? " (settle budget hit)" : "");
  }
  for (const SizeResult& s : report.sizes) {
    std::fprintf(out,
                 "  %u granules: neighbour-list skin %.3g d, near skin %.3g d; %llu list builds "
                 "and %llu particles over a list's capacity at them, %llu markings of the near "
                 "part, in the %u timed substeps\n",
                 s.granules, double(s.listSkin / particleDiameter(measure)),
                 double(s.listNearSkin / particleDiameter(measure)),
                 static_cast<unsigned long long>(s.listBuilds),
                 static_cast<unsigned long long>(s.listOverflows),
                 static_cast<unsigned long long>(s.listNearMarkings), s.steps);
  }
  for (const SizeResult& s : report.sizes) {
    if (s.settledFrom.empty()) continue;
    std::fprintf(out,
                 "  %u granules: the settled pile restored from %s (settle wall time above: the "
                 "restore; the run that settled it took %.0f s)\n",
                 s.granules, s.settledFrom.c_str(), s.settledFromWallSeconds);
  }
  for (const SizeResult& s : report.sizes) {
    if (!measure.sleep) break;
    std::fprintf(out,
                 "  %u granules, sleeping sand: %u substeps after the settling until all slept; "
                 "%u asleep at the start of timing, %u at its end; %llu of the timed list builds "
                 "sorted the sleepers again, the last sorted %u particles\n",
                 s.granules, s.sleepWaitSteps, s.asleepAtStart, s.asleepAtEnd,
                 static_cast<unsigned long long>(s.stillGridBuilds), s.movingGridParticles);
  }
  for (const SizeResult& s : report.sizes) {
    if (!measure.frames) break;
    std::fprintf(out,
                 "  %u granules, frames: the timed substeps in World::step frames of %u, the "
                 "statistics read after each; %llu of the %u substeps skipped as idle (all the "
                 "sand asleep), in %zu frames of %.3f ms each (median, wall)\n",
                 s.granules, measure.chunk, static_cast<unsigned long long>(s.idleSubsteps),
                 s.steps, s.idleFrameMs.size(), median(s.idleFrameMs));
  }
  for (const SizeResult& s : report.sizes) {
    if (s.rockParticles == 0) continue;
    std::fprintf(out,
                 "  %u granules, rock: a ball of %u particles (radius %.0f d) rolled across the "
                 "pile at %.1f m/s from the start of timing\n",
                 s.granules, s.rockParticles, double(kRockRadius), double(measure.rockSpeed));
  }
  for (const SizeResult& s : report.sizes) {
    if (s.timeline.empty()) continue;
    printTimeline(out, s);
  }
  if (!measure.kernelTimes) {
    std::fprintf(out, "  kernel timer queries off (--no-kernel-times)\n");
  }
}

}  // namespace sandphys::bench
