// The dune experiment of the validation report: two columns poured side by side.
#include "experiments.h"
#include "scenes/dunes.h"

namespace sandphys::validation {

namespace {

constexpr double kLongestRunSeconds = 20.0;

}  // namespace

nlohmann::json duneProfile(const ExperimentContext& context, const DuneOptions& options) {
  scenes::Dunes::Config config;
  config.granules = options.granulesPerColumn;
  config.separation = options.separation;
  scenes::Dunes scene(config);
  const samples::RunSummary run = runToEnd(context, scene, kLongestRunSeconds);
  const double d = config.particleDiameter;
  const scenes::Dunes::Profile profile = scene.profile(run.bodies);
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : profile.points) points.push_back({p[0] / d, p[1] / d});
  auto point = [&](const std::array<double, 2>& p) {
    return nlohmann::json{{"x_d", p[0] / d}, {"height_d", p[1] / d}};
  };
  nlohmann::json result = runFacts(run);
  result.update({{"granules_per_column", options.granulesPerColumn},
                 {"separation_d", options.separation},
                 {"profile_d", points},
                 {"left_crest", point(profile.leftCrest)},
                 {"right_crest", point(profile.rightCrest)},
                 {"saddle", point(profile.saddle)}});
  return result;
}

}  // namespace sandphys::validation
