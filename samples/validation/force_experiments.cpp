// The force experiments of the validation report: contact-force distributions of a settled and
// of a compressed pile, the contact network's structure, and the stress-strain loop.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <sandphys/analysis.h>

#include "experiments.h"
#include "scenes/compression.h"

namespace sandphys::validation {

namespace {

constexpr double kLongestRunSeconds = 30.0;
// Tail fits use the normalised forces from the mean up (the paper fits the tails, f > 1).
constexpr double kTailFrom = 1.0;

// Contacts between two granules, at particle or at granule level.
struct ContactSet {
  std::vector<double> normal;      // N
  std::vector<double> tangential;  // N
  std::vector<Vec3> points;        // m
  std::vector<Vec3> directions;    // unit normals
};

std::map<std::uint32_t, const BodyState*> granulesByIndex(const scenes::Compression::Snapshot& s) {
  std::map<std::uint32_t, const BodyState*> granules;
  for (const BodyState& body : s.bodies) {
    if (body.granule && body.alive) granules[body.id.index] = &body;
  }
  return granules;
}

ContactSet particleLevel(const scenes::Compression::Snapshot& snapshot) {
  const auto granules = granulesByIndex(snapshot);
  ContactSet set;
  for (const ContactRecord& c : snapshot.contacts) {
    if (!c.bodyB.isValid() || !granules.count(c.bodyA.index) || !granules.count(c.bodyB.index)) {
      continue;
    }
    set.normal.push_back(c.normalForce);
    set.tangential.push_back(length(c.tangentialForce));
    set.points.push_back(c.point);
    set.directions.push_back(c.normal);
  }
  return set;
}

// The contacts of each pair of granules summed into one force on the pair's first granule; its
// normal part is along the line between the two centres.
ContactSet granuleLevel(const scenes::Compression::Snapshot& snapshot) {
  const auto granules = granulesByIndex(snapshot);
  std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> sums;
  for (const ContactRecord& c : snapshot.contacts) {
    if (!c.bodyB.isValid() || !granules.count(c.bodyA.index) || !granules.count(c.bodyB.index)) {
      continue;
    }
    const Vec3 force = c.normalForce * c.normal + c.tangentialForce;  // on A
    const std::uint32_t a = c.bodyA.index;
    const std::uint32_t b = c.bodyB.index;
    const bool aFirst = a < b;
    Vec3& sum = sums[aFirst ? std::pair{a, b} : std::pair{b, a}];
    sum = sum + (aFirst ? force : -1.0f * force);
  }
  ContactSet set;
  for (const auto& [pair, force] : sums) {
    const Vec3 a = granules.at(pair.first)->position;
    const Vec3 b = granules.at(pair.second)->position;
    const Vec3 axis = a - b;
    const float distance = length(axis);
    if (distance == 0.0f) continue;
    const Vec3 u = (1.0f / distance) * axis;
    const float fn = dot(force, u);
    if (!(fn > 0.0f)) continue;  // a pair pulled together: no compressive contact
    set.normal.push_back(fn);
    set.tangential.push_back(length(force - fn * u));
    set.points.push_back(0.5f * (a + b));
    set.directions.push_back(u);
  }
  return set;
}

template <typename Fit>
nlohmann::json tryFit(Fit fit) {
  try {
    return fit();
  } catch (const InvalidArgument& error) {
    return {{"error", error.what()}};
  }
}

// The normalised distribution of `values` and the paper's fits to it.
nlohmann::json distribution(const std::vector<double>& values) {
  nlohmann::json result = {{"count", values.size()}};
  if (values.size() < 2) return result;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  result["mean_n"] = mean;
  if (!(mean > 0.0)) return result;
  const std::vector<double> f = analysis::normalisedByMean(values);
  const analysis::Density density = analysis::probabilityDensity(f);
  result["centres"] = density.centres;
  result["density"] = density.density;
  result["exponential"] = tryFit([&] {
    const analysis::ExponentialFit fit = analysis::fitExponentialTail(density, {.from = kTailFrom});
    return nlohmann::json{{"a", fit.a}, {"b", fit.b}, {"r2", fit.rSquared}};
  });
  result["gaussian"] = tryFit([&] {
    const analysis::GaussianFit fit = analysis::fitGaussianTail(density, {.from = kTailFrom});
    return nlohmann::json{{"beta", fit.beta}, {"alpha", fit.alpha}, {"r2", fit.rSquared}};
  });
  std::vector<double> positive;
  for (double v : f) {
    if (v > 0.0) positive.push_back(v);
  }
  result["gamma"] = tryFit([&] {
    const analysis::GammaFit fit = analysis::fitGamma(positive);
    return nlohmann::json{{"shape", fit.shape}, {"scale", fit.scale}};
  });
  return result;
}

nlohmann::json forces(const scenes::Compression::Snapshot& snapshot, double d, bool structure) {
  const ContactSet particles = particleLevel(snapshot);
  const ContactSet granules = granuleLevel(snapshot);
  nlohmann::json result = {{"time_s", snapshot.time},
                           {"particles",
                            {{"normal", distribution(particles.normal)},
                             {"tangential", distribution(particles.tangential)}}},
                           {"granules",
                            {{"normal", distribution(granules.normal)},
                             {"tangential", distribution(granules.tangential)}}}};
  if (!structure || granules.normal.size() < 2) return result;
  result["contact_angles"] = tryFit([&] {
    const analysis::AngleDistribution angles = analysis::contactAngles(granules.directions, 9);
    return nlohmann::json{
        {"degrees", angles.degrees}, {"density", angles.density}, {"isotropic", angles.isotropic}};
  });
  result["networks"] = tryFit([&] {
    const analysis::NetworkFractions split = analysis::networkFractions(granules.normal, 0.1, 4.0);
    return nlohmann::json{
        {"threshold", split.threshold}, {"contacts", split.contacts}, {"force", split.force}};
  });
  result["correlation"] = tryFit([&] {
    const analysis::ForceCorrelation g =
        analysis::forceCorrelation(particles.points, particles.normal, 0.5 * d, 10.0 * d);
    std::vector<double> distance;
    for (double r : g.distance) distance.push_back(r / d);
    return nlohmann::json{
        {"distance_d", distance}, {"correlation", g.correlation}, {"pairs", g.pairs}};
  });
  return result;
}

}  // namespace

nlohmann::json compressionAndForces(const ExperimentContext& context,
                                    const CompressionOptions& options) {
  nlohmann::json runs = nlohmann::json::array();
  for (const float friction : {options.friction, 0.0f}) {
    scenes::Compression::Config config;
    config.layers = options.layers;
    config.radius = options.radius;
    config.maxStress = options.maxStress;
    config.friction = friction;
    scenes::Compression scene(config);
    const samples::RunSummary run = runToEnd(context, scene, kLongestRunSeconds);
    const double d = config.particleDiameter;
    nlohmann::json curve = nlohmann::json::array();
    const scenes::SceneSeries stressStrain = scene.series().at(0);
    for (const auto& point : stressStrain.points) curve.push_back({point[0], point[1]});
    nlohmann::json entry = runFacts(run);
    entry.update({{"friction", friction},
                  {"granules", scene.granules()},
                  {"stress_strain", curve},
                  {"turn_index", scene.turnIndex()}});
    // max_strain, residual_strain and recovered_fraction.
    for (const scenes::SceneMetric& derived : stressStrain.derived)
      entry[derived.name] = derived.value;
    if (scene.atRest().time >= 0.0) entry["rest"] = forces(scene.atRest(), d, true);
    if (scene.atPeak().time >= 0.0) entry["peak"] = forces(scene.atPeak(), d, false);
    runs.push_back(std::move(entry));
  }
  return {{"layers", options.layers},
          {"radius_d", options.radius},
          {"max_stress_pa", options.maxStress},
          {"runs", runs}};
}

}  // namespace sandphys::validation
