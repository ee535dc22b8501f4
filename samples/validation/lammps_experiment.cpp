// The angle of repose of the reservoir-and-scupper setup run by sandphys and by LAMMPS from one
// exported state (issue 20, point 4): each μ's run is exported (exportLammps) the frame its gate
// rises; sandphys runs on to the scene's end, LAMMPS the same simulated span from the deck; both
// final states are measured with the scene's own heapAngle and granule counts.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <sandphys/analysis.h>
#include <sandphys/lammps_export.h>
#include <sandphys/lammps_run.h>

#include "experiments.h"
#include "scenes/repose_scupper.h"

namespace sandphys::validation {

namespace {

using Clock = std::chrono::steady_clock;

// Longest run of sandphys, s simulated: the reservoir settles in a second or two, the drain ends
// at the latest maxDrainSeconds after the gate rises.
constexpr double kLongestRunSeconds = 60.0;
// The deck's own span and output interval, s; the run's span is given on lmp's command line.
constexpr double kDeckSeconds = 1.0;
constexpr double kOutputSeconds = 0.01;

std::string number(double value, const char* format = "%.9g") {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// The clumps of a LAMMPS run as the scene's measures take granules.
std::vector<BodyState> granulesAt(const std::vector<Vec3>& centres) {
  std::vector<BodyState> bodies(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) bodies[i].position = centres[i];
  return bodies;
}

// The angle and the granule counts of one code's final state, as the scene measures its own.
nlohmann::json measure(const scenes::ReposeScupper& scene, const std::vector<BodyState>& bodies,
                       std::uint32_t granules) {
  const scenes::ReposeScupper::GranuleCounts counts = scene.countGranules(bodies);
  nlohmann::json entry = {{"granules_in_sump", counts.sump},
                          {"granules_in_reservoir", counts.reservoir},
                          {"granules_elsewhere", counts.alive - counts.sump - counts.reservoir},
                          {"granules_lost", granules - std::min(granules, counts.alive)}};
  try {
    const analysis::HeapAngle heap = scene.heapAngle(bodies);
    entry["angle_deg"] = heap.degrees;
    entry["angle_fit_r2"] = heap.fit.line.rSquared;
    entry["peak_height_m"] = heap.peakHeight;
    entry["flank_points"] = heap.radius.size();
  } catch (const InvalidArgument& error) {
    entry["angle_error"] = error.what();
  }
  return entry;
}

nlohmann::json compareAt(const ExperimentContext& context, const LammpsReposeOptions& options,
                         double mu) {
  scenes::ReposeScupper::Config config;
  config.friction = static_cast<float>(mu);
  config.settleSpeed = options.settleSpeed;
  scenes::ReposeScupper scene(config);
  scene.setContactLaw(context.contactLaw);
  const std::filesystem::path dir = options.dir / ("mu_" + number(mu, "%g"));

  // sandphys: to the scene's end, with the deck written the frame the gate rises.
  double exportTime = -1.0;
  Clock::time_point exportedAt;
  Clock::time_point endedAt;
  LammpsExportSummary deck;
  samples::RunHooks hooks;
  hooks.afterFrame = [&](World& world, std::uint64_t) {
    if (exportTime >= 0.0 || scene.releasedAt() < 0.0) return;
    exportTime = world.simulatedTime();
    deck = exportLammps(
        world, dir,
        {.runSeconds = kDeckSeconds,
         .outputSeconds = kOutputSeconds,
         .notes = {"the repose-scupper scene's gate has risen at t = " +
                   number(scene.releasedAt()) + " s (mu = " + number(mu, "%g") +
                   "), the frame this deck was written: the scupper stands open here as in "
                   "sandphys, which runs on from this state until the sump's pile is at rest "
                   "(rms speed below " +
                   number(options.settleSpeed, "%g") +
                   " m/s) and then measures the angle of repose; sandphys-validation --only "
                   "lammps-repose runs this deck for the same span"}});
    exportedAt = Clock::now();
  };
  hooks.atEnd = [&](World&, std::uint64_t) { endedAt = Clock::now(); };
  std::fprintf(stderr, "lammps-repose: mu = %g: sandphys\n", mu);
  const auto frames = static_cast<std::uint64_t>(kLongestRunSeconds / context.frameDt);
  const samples::RunSummary run =
      samples::runScene(context.gpu, scene, frames, context.frameDt, true, context.progress, hooks);
  context.progress.finish();
  if (exportTime < 0.0) {
    throw std::runtime_error("lammps-repose: mu = " + number(mu, "%g") +
                             ": the gate never rose in " + number(run.stats.simulatedTime, "%g") +
                             " s");
  }
  const double endTime = run.stats.simulatedTime;
  const double span = endTime - exportTime;

  nlohmann::json ours = measure(scene, run.bodies, config.granules);
  ours.update({{"wall_seconds", std::chrono::duration<double>(endedAt - exportedAt).count()},
               {"kinetic_energy_j", run.stats.kineticEnergy},
               {"end_time_s", endTime},
               {"status", scene.status()},
               {"finished", run.sceneFinished},
               {"max_overlap_d", run.maxOverlap / run.particleDiameter},
               {"time_step_s", run.timeStep}});

  // LAMMPS: the deck for the same span, from its folder.
  std::filesystem::remove(dir / "log.lammps");
  std::filesystem::remove(dir / "final.dump");
  const std::string command = lammpsCommand(dir, options.ranks, span);
  std::fprintf(stderr, "lammps-repose: mu = %g: %s (%.3f s simulated)\n", mu, command.c_str(),
               span);
  const Clock::time_point lammpsStart = Clock::now();
  const LammpsRun lammpsRun = runLammpsDeck(dir, options.ranks, span);
  const double lammpsWall = std::chrono::duration<double>(Clock::now() - lammpsStart).count();
  nlohmann::json theirs = measure(scene, granulesAt(lammpsRun.clumpCentres), config.granules);
  theirs.update({{"wall_seconds", lammpsWall},
                 {"kinetic_energy_j", lammpsRun.thermo.back().kineticEnergy},
                 {"end_time_s", exportTime + lammpsRun.thermo.back().time},
                 {"ranks", options.ranks},
                 {"version", lammpsRun.version}});

  nlohmann::json entry = {{"friction", mu},
                          {"export_time_s", exportTime},
                          {"span_s", span},
                          {"dir", dir.string()},
                          {"lammps_command", command},
                          {"deck_not_mapped", deck.notMapped},
                          {"sandphys", ours},
                          {"lammps", theirs}};
  if (ours.contains("angle_deg") && theirs.contains("angle_deg")) {
    entry["angle_difference_deg"] =
        theirs["angle_deg"].get<double>() - ours["angle_deg"].get<double>();
  }
  return entry;
}

}  // namespace

nlohmann::json lammpsRepose(const ExperimentContext& context, const LammpsReposeOptions& options) {
  nlohmann::json runs = nlohmann::json::array();
  for (double mu : options.frictions) runs.push_back(compareAt(context, options, mu));
  const scenes::ReposeScupper::Config geometry;
  return {{"granules", geometry.granules},
          {"particle_diameter_m", geometry.particleDiameter},
          {"settle_speed_m_s", options.settleSpeed},
          {"wall_friction", geometry.wallFriction},
          {"geometry_d",
           {{"depth", geometry.depth},
            {"reservoir_width", geometry.reservoirWidth},
            {"ledge", geometry.ledge},
            {"outlet", geometry.outlet},
            {"sump_length", geometry.sumpLength}}},
          {"lammps_ranks", options.ranks},
          {"lammps_dir", options.dir.string()},
          {"runs", runs}};
}

}  // namespace sandphys::validation
