// The hourglass experiments of the validation report: flow rate against friction and against
// the outlet diameter, with Beverloo's law fitted by the library.
#include <cmath>
#include <string>

#include <sandphys/analysis.h>

#include "experiments.h"
#include "scenes/hourglass.h"

namespace sandphys::validation {

namespace {

// Longest drain, s simulated: the fill settles within a second or two, then drains.
constexpr double kLongestRunSeconds = 20.0;

// The paper's fit of Fig. 24: W = 7.94 (D - 4.107)^{5/2}, W in grains/s and D in d.
constexpr double kPaperBeverlooC = 7.94;
constexpr double kPaperBeverlooK = 4.107;

nlohmann::json drain(const ExperimentContext& context, const scenes::Hourglass::Config& config) {
  scenes::Hourglass scene(config);
  const samples::RunSummary run = runToEnd(context, scene, kLongestRunSeconds);
  const scenes::Hourglass::FlowFit fit = scene.flowFit();
  nlohmann::json remaining = nlohmann::json::array();
  for (const auto& point : scene.remaining()) remaining.push_back({point[0], point[1]});
  nlohmann::json entry = runFacts(run);
  entry.update({{"friction", config.friction},
                {"outlet_d", config.outlet},
                {"granules_at_release", scene.granulesAtRelease()},
                {"flow_rate", fit.rate},
                {"flow_rate_r2", fit.rSquared},
                {"steady_start_s", fit.start},
                {"steady_end_s", fit.end},
                {"steady_samples", fit.samples},
                {"remaining", remaining}});
  return entry;
}

scenes::Hourglass::Config hourglass(std::uint32_t granules, float outlet, float friction) {
  scenes::Hourglass::Config config;
  config.granules = granules;
  config.outlet = outlet;
  config.friction = friction;
  return config;
}

}  // namespace

nlohmann::json flowAgainstFriction(const ExperimentContext& context,
                                   const FlowFrictionOptions& options) {
  nlohmann::json runs = nlohmann::json::array();
  for (double mu : options.frictions) {
    runs.push_back(
        drain(context, hourglass(options.granules, options.outlet, static_cast<float>(mu))));
  }
  return {{"granules", options.granules},
          {"outlet_d", options.outlet},
          {"wall_friction", scenes::Hourglass::Config{}.wallFriction},
          {"runs", runs}};
}

nlohmann::json flowAgainstOutlet(const ExperimentContext& context,
                                 const FlowOutletOptions& options) {
  nlohmann::json runs = nlohmann::json::array();
  std::vector<double> outlets;
  std::vector<double> rates;
  for (double outlet : options.outlets) {
    nlohmann::json run =
        drain(context, hourglass(options.granules, static_cast<float>(outlet), options.friction));
    // A jammed outlet has no steady part and no rate; Beverloo's law is about flowing ones.
    if (run["flow_rate"].get<double>() > 0.0) {
      outlets.push_back(outlet);
      rates.push_back(run["flow_rate"].get<double>());
    }
    runs.push_back(std::move(run));
  }
  nlohmann::json result = {{"granules", options.granules},
                           {"friction", options.friction},
                           {"wall_friction", scenes::Hourglass::Config{}.wallFriction},
                           {"runs", runs},
                           {"paper", {{"c", kPaperBeverlooC}, {"k", kPaperBeverlooK}}}};
  try {
    const analysis::BeverlooFit fit = analysis::fitBeverloo(outlets, rates);
    result["beverloo"] = {{"c", fit.c}, {"k", fit.k}, {"r2", fit.rSquared}};
  } catch (const InvalidArgument& error) {
    result["beverloo_error"] = error.what();
  }
  return result;
}

}  // namespace sandphys::validation
