// The angle-of-repose experiment of the validation report: heaps poured at several μ, their
// angles, and a power law fitted by the library.
#include <string>

#include <sandphys/analysis.h>

#include "experiments.h"
#include "scenes/repose_heap.h"

namespace sandphys::validation {

namespace {

constexpr double kLongestRunSeconds = 20.0;
// The paper's Fig. 22: a power law in μ with this exponent.
constexpr double kPaperExponent = 0.51;

}  // namespace

nlohmann::json reposeAgainstFriction(const ExperimentContext& context,
                                     const ReposeOptions& options) {
  nlohmann::json runs = nlohmann::json::array();
  std::vector<double> frictions;
  std::vector<double> angles;
  for (double mu : options.frictions) {
    scenes::ReposeHeap::Config config;
    config.granules = options.granules;
    config.friction = static_cast<float>(mu);
    scenes::ReposeHeap scene(config);
    const samples::RunSummary run = runToEnd(context, scene, kLongestRunSeconds);
    nlohmann::json entry = {{"friction", mu},
                            {"finished", run.sceneFinished},
                            {"wall_seconds", run.wallSeconds},
                            {"simulated_seconds", run.stats.simulatedTime}};
    try {
      const analysis::HeapAngle heap = scene.heapAngle(run.bodies);
      entry["angle_deg"] = heap.degrees;
      entry["angle_fit_r2"] = heap.fit.line.rSquared;
      entry["fit_intercept_m"] = heap.fit.line.intercept;
      entry["fit_slope"] = heap.fit.line.slope;
      entry["peak_height_m"] = heap.peakHeight;
      entry["flank_radius_m"] = heap.radius;
      entry["flank_height_m"] = heap.height;
      entry["flank_weight"] = heap.fit.weights;
      if (heap.degrees > 0.0) {
        frictions.push_back(mu);
        angles.push_back(heap.degrees);
      }
    } catch (const InvalidArgument& error) {
      entry["angle_error"] = error.what();
    }
    runs.push_back(std::move(entry));
  }
  nlohmann::json result = {{"granules", options.granules},
                           {"particle_diameter_m", scenes::ReposeHeap::Config{}.particleDiameter},
                           {"runs", runs},
                           {"paper", {{"exponent", kPaperExponent}}}};
  try {
    const analysis::PowerLawFit fit = analysis::fitPowerLaw(frictions, angles);
    result["power_law"] = {
        {"coefficient", fit.coefficient}, {"exponent", fit.exponent}, {"r2", fit.rSquared}};
  } catch (const InvalidArgument& error) {
    result["power_law_error"] = error.what();
  }
  return result;
}

}  // namespace sandphys::validation
