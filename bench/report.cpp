#include "report.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <fstream>

#include <sandphys/error.h>

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

const KernelStep* findKernel(const SizeResult& size, const std::string& name) {
  for (const KernelStep& kernel : size.kernels) {
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
  const double granules = size.granules;
  return {
      {"granules", size.granules},
      {"particles", size.particles},
      {"floor_particles", size.floorParticles},
      {"particle_capacity", size.particleCapacity},
      {"contacts", size.measured.contacts},
      {"contacts_per_granule", size.measured.contactsPerGranule},
      {"cundall_number", size.cundallNumber()},
      {"microseconds_per_granule_step", size.microsecondsPerGranuleStep()},
      {"simulated_seconds_per_wall_second", size.simulatedPerWallSecond()},
      {"gpu_memory_bytes", size.gpuMemoryBytes},
      {"gpu_memory_bytes_per_granule", granules > 0 ? size.gpuMemoryBytes / granules : 0.0},
      {"time_step_s", shortest(size.timeStep)},
      {"steps", size.steps},
      {"steps_planned", size.plan.steps},
      {"budget_hit", size.budgetHit},
      {"wall_seconds", size.wallSeconds},
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
      {"layout",
       {{"spacing_d", size.layout.spacing / d},
        {"columns", size.layout.columns},
        {"full_layers", size.layout.fullLayers},
        {"top_layer_granules", size.layout.topLayerGranules},
        {"column_top_d", size.layout.columnTop / d},
        {"wall_height_d", size.layout.wallHeight},
        {"wall_raised", size.layout.wallRaised}}},
      {"settle",
       {{"steps", size.settleSteps},
        {"steps_planned", size.plan.settleSteps},
        {"simulated_seconds", size.settled.simulatedSeconds},
        {"wall_seconds", size.settleWallSeconds},
        {"budget_hit", size.settleBudgetHit}}},
      {"state",
       {{"built", pileStateJson(size.built)},
        {"settled", pileStateJson(size.settled)},
        {"measured", pileStateJson(size.measured)}}},
  };
}

}  // namespace

nlohmann::json reportJson(const BenchOptions& options, const BenchReport& report) {
  const MeasureOptions& measure = options.measure;
  nlohmann::json sizes = nlohmann::json::array();
  for (const SizeResult& size : report.sizes) {
    sizes.push_back(sizeJson(size, measure.pile.particleDiameter));
  }
  return {
      {"benchmark", "cylinder-pile"},
      {"description",
       "settled cylinder pile of Longmore et al. 2013: smooth wall of radius 50 d, rough "
       "particle floor; built as a dense lattice from the floor up and settled before timing"},
      {"gpu", report.gpu},
      {"hardware_threads", report.hardwareThreads},
      {"options",
       {{"packing", packingName(measure.pile.packing)},
        {"particle_diameter_m", shortest(measure.pile.particleDiameter)},
        {"cylinder_radius_d", shortest(measure.pile.cylinderRadius)},
        {"cylinder_height_d", shortest(measure.pile.cylinderHeight)},
        {"spacing_d", shortest(measure.pile.spacing)},
        {"jitter", shortest(measure.pile.jitter)},
        {"seed", measure.pile.seed},
        {"chunk", measure.chunk},
        {"budget_seconds", measure.budgetSeconds},
        {"settle_budget_seconds", measure.settleBudgetSeconds},
        {"kernel_times", measure.kernelTimes}}},
      {"sizes", sizes},
  };
}

void writeJson(const std::string& path, const nlohmann::json& json) {
  std::ofstream file(path);
  file << json.dump(2) << '\n';
  if (!file) throw Error("--json: cannot write '" + path + "'");
}

void printReport(std::FILE* out, const BenchOptions& options, const BenchReport& report) {
  const MeasureOptions& measure = options.measure;
  const double d = measure.pile.particleDiameter;
  std::fprintf(out,
               "sandphys-bench: settled cylinder pile (wall radius %g d, rough particle floor, "
               "smooth wall), d = %g m, %s packing\nGPU: %s (%u hardware threads)\n\n",
               double(measure.pile.cylinderRadius), d,
               std::string(packingName(measure.pile.packing)).c_str(), report.gpu.c_str(),
               report.hardwareThreads);

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
    char top[48];
    std::snprintf(top, sizeof top, "%.0f->%.0f->%.0f", s.layout.columnTop / d, s.settled.pileTop,
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
    std::fprintf(out, "\nGPU time per substep, ms (GL timestamp queries):\n%-20s", "kernel");
    for (const SizeResult& s : report.sizes) std::fprintf(out, " %10u", s.granules);
    std::fprintf(out, "\n");
    for (const std::string& name : names) {
      std::fprintf(out, "%-20s", name.c_str());
      for (const SizeResult& s : report.sizes) {
        const KernelStep* kernel = findKernel(s, name);
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
  if (!measure.kernelTimes) {
    std::fprintf(out, "  kernel timer queries off (--no-kernel-times)\n");
  }
}

}  // namespace sandphys::bench
