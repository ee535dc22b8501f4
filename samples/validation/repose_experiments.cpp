// The angle-of-repose experiments of the validation report: heaps poured at several μ, and piles
// run into a sump through a scupper (the paper's setup), their angles, and power laws fitted by
// the library.
#include <cstdint>
#include <string>
#include <vector>

#include <sandphys/analysis.h>

#include "experiments.h"
#include "scenes/repose_heap.h"
#include "scenes/repose_scupper.h"

namespace sandphys::validation {

namespace {

constexpr double kLongestRunSeconds = 20.0;
// The paper's Fig. 22: a power law in μ with this exponent.
constexpr double kPaperExponent = 0.51;

// One run per μ of a scene with a heapAngle (ReposeHeap, ReposeScupper) made by `makeScene`, the
// angle of each, and the power law through them; `granules` and the scene's own metrics go with
// each run.
template <typename SceneType, typename MakeScene>
nlohmann::json angleSweep(const ExperimentContext& context, std::uint32_t granules,
                          const std::vector<double>& frictionList, MakeScene makeScene) {
  nlohmann::json runs = nlohmann::json::array();
  std::vector<double> frictions;
  std::vector<double> angles;
  for (double mu : frictionList) {
    SceneType scene = makeScene(static_cast<float>(mu));
    const samples::RunSummary run = runToEnd(context, scene, kLongestRunSeconds);
    nlohmann::json entry = runFacts(run);
    entry.update({{"friction", mu}, {"kinetic_energy_j", run.stats.kineticEnergy}});
    for (const scenes::SceneMetric& metric : scene.metrics(run.bodies)) {
      if (metric.name.starts_with("granules_") || metric.name == "settled") {
        entry[metric.name] = metric.value;
      }
    }
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
      // A power law through the origin: μ = 0 is measured but has no logarithm.
      if (mu > 0.0 && heap.degrees > 0.0) {
        frictions.push_back(mu);
        angles.push_back(heap.degrees);
      }
    } catch (const InvalidArgument& error) {
      entry["angle_error"] = error.what();
    }
    runs.push_back(std::move(entry));
  }
  nlohmann::json result = {
      {"granules", granules},
      {"particle_diameter_m", typename SceneType::Config{}.particleDiameter},
      {"granule_mass_kg",
       tetrahedronTemplate(typename SceneType::Config{}.particleDiameter, Material{}.density).mass},
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

}  // namespace

nlohmann::json reposeAgainstFriction(const ExperimentContext& context,
                                     const ReposeOptions& options) {
  const float floorRadius =
      scenes::ReposeHeap::floorRadiusHolding(options.granules, options.lowestAngle);
  nlohmann::json result =
      angleSweep<scenes::ReposeHeap>(context, options.granules, options.frictions, [&](float mu) {
        scenes::ReposeHeap::Config config;
        config.granules = options.granules;
        config.friction = mu;
        config.floorRadius = floorRadius;
        config.settleSpeed = options.settleSpeed;
        config.maxSettleSeconds = options.maxSettleSeconds;
        return scenes::ReposeHeap(config);
      });
  result["floor_radius_d"] = floorRadius;
  result["settle_speed_m_s"] = options.settleSpeed;
  return result;
}

nlohmann::json scupperAgainstFriction(const ExperimentContext& context,
                                      const ScupperOptions& options) {
  nlohmann::json result = angleSweep<scenes::ReposeScupper>(
      context, options.granules, options.frictions, [&](float mu) {
        scenes::ReposeScupper::Config config;
        config.granules = options.granules;
        config.friction = mu;
        config.settleSpeed = options.settleSpeed;
        return scenes::ReposeScupper(config);
      });
  const scenes::ReposeScupper::Config geometry;
  result["settle_speed_m_s"] = options.settleSpeed;
  result["wall_friction"] = geometry.wallFriction;
  result["geometry_d"] = {{"depth", geometry.depth},
                          {"reservoir_width", geometry.reservoirWidth},
                          {"ledge", geometry.ledge},
                          {"outlet", geometry.outlet},
                          {"sump_length", geometry.sumpLength}};
  return result;
}

}  // namespace sandphys::validation
