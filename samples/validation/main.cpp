// sandphys-validation: runs the validation experiments of Longmore et al. 2013 (section 6)
// headless and writes their measurements and fits to one JSON file, from which
// scripts/validation/make_report.py draws the plots and writes docs/validation/README.md.
// scripts/validation-report.sh runs both.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "experiments.h"

namespace {

using namespace sandphys;
using namespace sandphys::validation;

// Run by default.
const std::vector<std::string> kExperiments{"flow-friction",  "flow-outlet", "repose",
                                            "repose-scupper", "dunes",       "compression"};
// Run only when named in --only: lammps-repose needs lmp and mpirun.
const std::vector<std::string> kOnDemand{"lammps-repose"};

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void write(const std::filesystem::path& path, const nlohmann::json& results) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path);
  out << results.dump(1) << '\n';
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

namespace sandphys::validation {

samples::RunSummary runToEnd(const ExperimentContext& context, scenes::Scene& scene,
                             double maxSeconds) {
  const auto frames = static_cast<std::uint64_t>(maxSeconds / context.frameDt);
  scene.setContactLaw(context.contactLaw);
  samples::RunSummary run =
      samples::runScene(context.gpu, scene, frames, context.frameDt, true, context.progress);
  context.progress.finish();
  return run;
}

nlohmann::json runFacts(const samples::RunSummary& run) {
  return {{"finished", run.sceneFinished},
          {"wall_seconds", run.wallSeconds},
          {"simulated_seconds", run.stats.simulatedTime},
          {"max_overlap_d", run.maxOverlap / run.particleDiameter},
          {"granules_not_born", run.stats.granulesNotBorn},
          {"substeps_per_frame", run.frameDt / run.timeStep}};
}

}  // namespace sandphys::validation

int main(int argc, char** argv) {
  CLI::App app{
      "sandphys-validation: the paper's validation experiments (Longmore et al. 2013, section 6) "
      "run headless; writes the measurements and fits as JSON for "
      "scripts/validation/make_report.py"};
  std::string out = "build/validation/results.json";
  std::vector<std::string> only = kExperiments;
  std::vector<std::string> allExperiments = kExperiments;
  allExperiments.insert(allExperiments.end(), kOnDemand.begin(), kOnDemand.end());
  FlowFrictionOptions flowFriction;
  FlowOutletOptions flowOutlet;
  ReposeOptions repose;
  ScupperOptions scupper;
  DuneOptions dunes;
  CompressionOptions compression;
  LammpsReposeOptions lammps;
  bool quiet = false;
  app.add_option("--out", out, "results file (JSON)")->capture_default_str();
  app.add_option("--only", only,
                 "experiments to run, comma-separated (lammps-repose, which needs lmp and "
                 "mpirun, runs only when named)")
      ->delimiter(',')
      ->check(CLI::IsMember(allExperiments))
      ->capture_default_str();
  app.add_option("--hourglass-granules", flowFriction.granules,
                 "granules in the funnel of every hourglass run")
      ->check(CLI::Range(1u, 1u << 28))
      ->capture_default_str();
  app.add_option("--flow-frictions", flowFriction.frictions,
                 "flow-friction: the grains' friction coefficients, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--flow-outlet", flowFriction.outlet, "flow-friction: outlet diameter, d")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--outlets", flowOutlet.outlets,
                 "flow-outlet: outlet diameters, d, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--outlet-friction", flowOutlet.friction, "flow-outlet: friction coefficient")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--heap-granules", repose.granules, "repose: granules poured into each heap")
      ->check(CLI::Range(1u, 1u << 28))
      ->capture_default_str();
  app.add_option("--heap-frictions", repose.frictions,
                 "repose: friction coefficients, comma-separated (μ = 0 is left out of the "
                 "power law)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--scupper-granules", scupper.granules,
                 "repose-scupper: granules in the reservoir of each run")
      ->check(CLI::Range(1u, 1u << 28))
      ->capture_default_str();
  app.add_option("--scupper-frictions", scupper.frictions,
                 "repose-scupper: friction coefficients of the grains, comma-separated (μ = 0 is "
                 "left out of the power law)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--dune-granules", dunes.granulesPerColumn,
                 "dunes: granules poured by each column")
      ->check(CLI::Range(1u, 1u << 28))
      ->capture_default_str();
  app.add_option("--dune-separation", dunes.separation, "dunes: distance between the columns, d")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--compression-layers", compression.layers,
                 "compression: lattice layers the pile is dropped from")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  app.add_option("--compression-radius", compression.radius,
                 "compression: radius of the cylinder, d")
      ->check(CLI::Range(2.0, 1000.0))
      ->capture_default_str();
  app.add_option("--max-stress", compression.maxStress,
                 "compression: axial stress at which the plunger turns back, Pa")
      ->check(CLI::Range(1.0, 1e9))
      ->capture_default_str();
  std::string law = "hertz-mindlin";
  app.add_option("--contact-law", law,
                 "hertz-mindlin (the default) or paper (Longmore et al. 2013 as published)")
      ->check(CLI::IsMember({"hertz-mindlin", "paper"}))
      ->capture_default_str();
  app.add_option("--lammps-frictions", lammps.frictions,
                 "lammps-repose: the grains' friction coefficients, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--lammps-ranks", lammps.ranks,
                 "lammps-repose: MPI ranks of LAMMPS (1: no mpirun)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--lammps-dir", lammps.dir,
                 "lammps-repose: folder of the decks and LAMMPS's outputs (one mu_<μ> per μ; kept)")
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "no progress lines");
  CLI11_PARSE(app, argc, argv);
  flowOutlet.granules = flowFriction.granules;

  try {
    const std::set<std::string> chosen(only.begin(), only.end());
    const GpuContext gpu = GpuContext::headless();
    samples::ProgressLine progress(!quiet);
    const ExperimentContext context{gpu, progress, *scenes::contactLawFromName(law)};
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
    nlohmann::json results = {{"gpu", gpu.description()},
                              {"started", utcNow()},
                              {"command", command},
                              {"contact_law", law}};
    const auto start = std::chrono::steady_clock::now();
    auto run = [&](const std::string& name, auto experiment) {
      if (!chosen.count(name)) return;
      std::fprintf(stderr, "sandphys-validation: %s\n", name.c_str());
      results[name] = experiment();
      results["wall_seconds"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      write(out, results);  // after each experiment, so that a long run keeps what it has
    };
    run("flow-friction", [&] { return flowAgainstFriction(context, flowFriction); });
    run("flow-outlet", [&] { return flowAgainstOutlet(context, flowOutlet); });
    run("repose", [&] { return reposeAgainstFriction(context, repose); });
    run("repose-scupper", [&] { return scupperAgainstFriction(context, scupper); });
    run("dunes", [&] { return duneProfile(context, dunes); });
    run("compression", [&] { return compressionAndForces(context, compression); });
    run("lammps-repose", [&] { return lammpsRepose(context, lammps); });
    std::fprintf(stderr, "sandphys-validation: wrote %s\n", out.c_str());
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "sandphys-validation: " << error.what() << '\n';
    return 1;
  }
}
