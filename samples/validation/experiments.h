#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <sandphys/sandphys.h>
#include <nlohmann/json.hpp>

#include "app/progress.h"
#include "app/run.h"
#include "scenes/repose_scupper.h"
#include "scenes/scene.h"

namespace sandphys::validation {

/// What every experiment needs: the GPU, a progress line, the contact law and the frame length
/// of its runs.
struct ExperimentContext {
  const GpuContext& gpu;
  samples::ProgressLine& progress;
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
  double frameDt = 1.0 / 120.0;
};

/// Runs `scene` headless in a new World under context.contactLaw until it finishes or
/// `maxSeconds` have been simulated, with frames of context.frameDt.
samples::RunSummary runToEnd(const ExperimentContext& context, scenes::Scene& scene,
                             double maxSeconds);
/// What every run's entry in the results carries: finished, wall_seconds, simulated_seconds,
/// max_overlap_d (the largest overlap of the run over d), granules_not_born (emitted where a
/// granule already was) and substeps_per_frame.
nlohmann::json runFacts(const samples::RunSummary& run);

/// The hourglass against friction (the paper's Fig. 23): one fill per μ over a fixed outlet, each
/// drained; the granules remaining over time and the flow rate of the steady part.
struct FlowFrictionOptions {
  std::uint32_t granules = 2000;
  float outlet = 16.0f;  ///< d
  std::vector<double> frictions{0.0, 0.2, 0.4, 0.6, 0.8};
};
nlohmann::json flowAgainstFriction(const ExperimentContext& context,
                                   const FlowFrictionOptions& options);

/// The hourglass against the outlet diameter (the paper's Fig. 24) at one μ, and the fit of
/// Beverloo's law W = C (D − k)^{5/2} beside the paper's.
struct FlowOutletOptions {
  std::uint32_t granules = 2000;
  float friction = 0.2f;
  std::vector<double> outlets{8.0, 12.0, 16.0, 20.0, 24.0};  ///< d
};
nlohmann::json flowAgainstOutlet(const ExperimentContext& context,
                                 const FlowOutletOptions& options);

/// The angle of repose of poured heaps against friction (the paper's Fig. 22) and a power law
/// fitted to it beside the paper's exponent.
struct ReposeOptions {
  std::uint32_t granules = 1500;
  /// μ = 0 is measured but left out of the power law.
  std::vector<double> frictions{0.0, 0.1, 0.2, 0.4, 0.6, 0.8};
  /// The floor follows the granule count: a heap with its flank this steep ends short of the
  /// floor's edge (ReposeHeap::floorRadiusHolding), degrees; μ = 0 spreads wider, as it must.
  float lowestAngle = 10.0f;
  /// At rest below this rms speed, m/s: a tenth of the scenes' default, so that a heap still
  /// sagging is not measured as settled.
  float settleSpeed = 0.002f;
  /// Longest wait for rest after the pour, s.
  float maxSettleSeconds = 6.0f;
};
nlohmann::json reposeAgainstFriction(const ExperimentContext& context,
                                     const ReposeOptions& options);

/// The angle of repose in the sump of the paper's reservoir-and-scupper setup (Fig. 15) against
/// friction (Fig. 22), with the scene's default geometry, and its power law.
struct ScupperOptions {
  std::uint32_t granules = scenes::ReposeScupper::Config{}.granules;
  /// μ = 0 is measured but left out of the power law.
  std::vector<double> frictions{0.0, 0.1, 0.2, 0.4, 0.6, 0.8};
  /// At rest below this rms speed, m/s (as for ReposeOptions).
  float settleSpeed = 0.002f;
};
nlohmann::json scupperAgainstFriction(const ExperimentContext& context,
                                      const ScupperOptions& options);

/// The angle of repose of the reservoir-and-scupper setup (as ScupperOptions, the scene's default
/// geometry) run by sandphys and by LAMMPS from one state: for each μ, the World is exported with
/// exportLammps the frame the gate rises; sandphys runs on to the scene's end, LAMMPS runs the
/// deck for the same simulated span on `ranks` MPI ranks; both final states are measured with
/// ReposeScupper::heapAngle and its granule counts. Not run by default (it needs lmp and mpirun).
struct LammpsReposeOptions {
  std::vector<double> frictions{0.3, 0.6};
  int ranks = 2;
  /// The decks and LAMMPS's outputs, one folder mu_<μ> per μ; kept.
  std::filesystem::path dir = "build/validation/lammps";
  /// At rest below this rms speed, m/s (as ScupperOptions).
  float settleSpeed = ScupperOptions{}.settleSpeed;
};
nlohmann::json lammpsRepose(const ExperimentContext& context, const LammpsReposeOptions& options);

/// Two columns of sand poured side by side (the paper's Fig. 25): the dune's profile, its two
/// crests and the saddle between them.
struct DuneOptions {
  std::uint32_t granulesPerColumn = 1500;
  float separation = 24.0f;  ///< d
};
nlohmann::json duneProfile(const ExperimentContext& context, const DuneOptions& options);

/// A pile settled in a cylinder, then compressed by a plunger and released (the paper's Figs.
/// 17-21): contact-force distributions at rest (μ = 0.5 and μ = 0) and at the peak of the load,
/// at particle and at granule level, with their fits; the force-force correlation, the contact
/// angles and the weak and strong networks at rest; the stress-strain loop.
struct CompressionOptions {
  std::uint32_t layers = 16;
  float radius = 14.0f;        ///< d
  float maxStress = 20000.0f;  ///< Pa
  float friction = 0.5f;
};
nlohmann::json compressionAndForces(const ExperimentContext& context,
                                    const CompressionOptions& options);

}  // namespace sandphys::validation
