// The angle of repose of the reservoir-and-scupper setup run by sandphys and by LAMMPS from one
// exported state (issue 20, point 4): each μ's run is exported (exportLammps) the frame its gate
// rises; sandphys runs on to the scene's end, LAMMPS the same simulated span from the deck; both
// final states are measured with the scene's own heapAngle and granule counts.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sandphys/analysis.h>
#include <sandphys/lammps_export.h>

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

// What LAMMPS left in its folder: the clumps' centres at the end, the last thermo line's kinetic
// energy, and the version line of its log.
struct LammpsResult {
  std::vector<BodyState> bodies;
  std::optional<double> kineticEnergy;
  double simulatedSeconds = 0.0;
  std::string version;
};

LammpsResult readLammps(const std::filesystem::path& dir) {
  LammpsResult result;
  std::ifstream log(dir / "log.lammps");
  if (!log) throw std::runtime_error("no " + (dir / "log.lammps").string());
  std::string line;
  bool thermo = false;
  while (std::getline(log, line)) {
    if (result.version.empty() && line.rfind("LAMMPS (", 0) == 0) result.version = line;
    if (line.rfind("Step Time Atoms v_energy", 0) == 0) {
      thermo = true;
      continue;
    }
    if (line.rfind("Loop time", 0) == 0) thermo = false;
    if (!thermo) continue;
    std::istringstream fields(line);
    double step = 0.0, time = 0.0, atoms = 0.0, energy = 0.0;
    fields >> step >> time >> atoms >> energy;
    if (!fields) continue;  // a warning in the thermo block
    result.kineticEnergy = energy;
    result.simulatedSeconds = time;
  }
  // final.dump: id mol type x y z vx vy vz; the clumps' particles have mol > 0, and a clump's
  // centre of mass is the mean of its 4 particles.
  std::ifstream dump(dir / "final.dump");
  if (!dump) throw std::runtime_error("no " + (dir / "final.dump").string());
  struct Sum {
    double x = 0.0, y = 0.0, z = 0.0;
    int particles = 0;
  };
  std::map<long, Sum> clumps;
  bool atoms = false;
  while (std::getline(dump, line)) {
    if (line.rfind("ITEM: ATOMS", 0) == 0) {
      atoms = true;
      continue;
    }
    if (!atoms) continue;
    std::istringstream fields(line);
    long id = 0, mol = 0;
    int type = 0;
    double x = 0.0, y = 0.0, z = 0.0;
    fields >> id >> mol >> type >> x >> y >> z;
    if (!fields || mol <= 0) continue;
    Sum& sum = clumps[mol];
    sum.x += x;
    sum.y += y;
    sum.z += z;
    ++sum.particles;
  }
  for (const auto& [mol, sum] : clumps) {
    BodyState body;
    const double n = sum.particles;
    body.position = {static_cast<float>(sum.x / n), static_cast<float>(sum.y / n),
                     static_cast<float>(sum.z / n)};
    body.alive = true;
    body.granule = true;
    result.bodies.push_back(body);
  }
  return result;
}

// The angle and the granule counts of one code's final state, as the scene measures its own.
nlohmann::json measure(const scenes::ReposeScupper& scene, const std::vector<BodyState>& bodies,
                       std::uint32_t granules) {
  std::uint32_t sump = 0;
  std::uint32_t reservoir = 0;
  std::uint32_t present = 0;
  for (const BodyState& body : bodies) {
    if (!body.alive || !body.granule) continue;
    ++present;
    sump += scene.inSump(body.position) ? 1 : 0;
    reservoir += scene.inReservoir(body.position) ? 1 : 0;
  }
  nlohmann::json entry = {{"granules_in_sump", sump},
                          {"granules_in_reservoir", reservoir},
                          {"granules_elsewhere", present - sump - reservoir},
                          {"granules_lost", granules - std::min(granules, present)}};
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
  std::string lmp;
  if (options.ranks > 1) {
    lmp = "mpirun " + std::string(geteuid() == 0 ? "--allow-run-as-root " : "") +
          "--oversubscribe -np " + std::to_string(options.ranks) + ' ';
  }
  lmp += "lmp -in in.sandphys -var seconds " + number(span);
  const std::string command = "cd '" + dir.string() + "' && " + lmp + " > lammps.out 2>&1";
  std::fprintf(stderr, "lammps-repose: mu = %g: %s (%.3f s simulated)\n", mu, lmp.c_str(), span);
  const Clock::time_point lammpsStart = Clock::now();
  const int status = std::system(command.c_str());
  const double lammpsWall = std::chrono::duration<double>(Clock::now() - lammpsStart).count();
  if (status != 0) {
    throw std::runtime_error("lammps-repose: `" + command + "` failed (status " +
                             std::to_string(status) + "); see " + (dir / "lammps.out").string());
  }
  const LammpsResult lammpsRun = readLammps(dir);
  nlohmann::json theirs = measure(scene, lammpsRun.bodies, config.granules);
  theirs.update(
      {{"wall_seconds", lammpsWall},
       {"kinetic_energy_j", lammpsRun.kineticEnergy ? nlohmann::json(*lammpsRun.kineticEnergy)
                                                    : nlohmann::json(nullptr)},
       {"end_time_s", exportTime + lammpsRun.simulatedSeconds},
       {"ranks", options.ranks},
       {"version", lammpsRun.version}});

  nlohmann::json entry = {{"friction", mu},
                          {"export_time_s", exportTime},
                          {"span_s", span},
                          {"dir", dir.string()},
                          {"lammps_command", "cd " + dir.string() + " && " + lmp},
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
