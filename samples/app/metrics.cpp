#include "app/metrics.h"

#include <array>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace sandphys::samples {

namespace {

// A float as the shortest decimal that reads back to it (0.02f -> 0.02, not 0.0199999996), so
// that the JSON shows the value the user gave.
double shortest(float value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer - 1, value);
  if (ec != std::errc()) return value;
  *end = '\0';
  return std::strtod(buffer, nullptr);
}

nlohmann::json parameterValue(const scenes::SceneParameter& parameter) {
  return std::visit(
      [](auto* value) -> nlohmann::json {
        using T = std::remove_pointer_t<decltype(value)>;
        if constexpr (std::is_same_v<T, scenes::Count3>) {
          return nlohmann::json::array({(*value)[0], (*value)[1], (*value)[2]});
        } else if constexpr (std::is_same_v<T, float>) {
          return shortest(*value);
        } else {
          return *value;
        }
      },
      parameter.value);
}

// Ratio that stays finite for a run too short to time.
double perWallSecond(double amount, double wallSeconds) {
  return wallSeconds > 0.0 ? amount / wallSeconds : 0.0;
}

// Scene::bodies as a list of {name, position [x, y, z] m, orientation [w, x, y, z], speed m/s,
// tilt_deg}.
nlohmann::json bodiesJson(const std::vector<scenes::SceneBody>& bodies) {
  nlohmann::json list = nlohmann::json::array();
  for (const scenes::SceneBody& body : bodies) {
    list.push_back({
        {"name", body.name},
        {"position", {body.position.x, body.position.y, body.position.z}},
        {"orientation",
         {body.orientation.w, body.orientation.x, body.orientation.y, body.orientation.z}},
        {"speed", body.speed},
        {"tilt_deg", body.tiltDegrees},
    });
  }
  return list;
}

}  // namespace

nlohmann::json metricsJson(const RunSummary& summary, scenes::Scene& scene) {
  const WorldStats& stats = summary.stats;
  nlohmann::json metrics = {
      {"scene", summary.scene},
      {"granules", stats.granulesAlive},
      {"granules_asleep", stats.granulesAsleep},
      {"particles", stats.particles},
      {"body_slots", stats.bodies},
      {"frames", summary.frames},
      {"frame_dt", summary.frameDt},
      {"steps", stats.steps},
      {"time_step", shortest(summary.timeStep)},
      {"simulated_seconds", stats.simulatedTime},
      {"dropped_seconds", summary.droppedSeconds},
      {"wall_seconds", summary.wallSeconds},
      {"setup_seconds", summary.setupSeconds},
      {"cundall_number", perWallSecond(summary.granuleSteps, summary.wallSeconds)},
      {"seconds_simulated_per_wall_second",
       perWallSecond(stats.simulatedTime, summary.wallSeconds)},
      {"contacts", stats.contacts},
      {"kinetic_energy", stats.kineticEnergy},
      {"max_overlap_d", summary.maxOverlap / summary.particleDiameter},
      {"contact_law", scenes::contactLawName(summary.contactLaw)},
      {"youngs_modulus_pa", shortest(summary.youngsModulus)},
      {"max_speed_m_per_s", shortest(summary.maxSpeed)},
      {"penetration_clamps", stats.penetrationClamps},
      {"contact_slot_overflows", stats.contactSlotOverflows},
      {"velocity_clamps", stats.velocityClamps},
      {"granules_spawned", stats.granulesSpawned},
      {"granules_killed", stats.granulesKilled},
      {"granules_not_born", stats.granulesNotBorn},
      {"granules_lost", summary.granulesLost},
      {"particle_diameter", shortest(summary.particleDiameter)},
      {"gpu", summary.gpu},
      {"gpu_memory_bytes", summary.gpuMemoryBytes},
      {"scene_finished", summary.sceneFinished},
  };
  nlohmann::json parameters = nlohmann::json::object();
  for (const scenes::SceneParameter& parameter : scene.parameters()) {
    parameters[parameter.name] = parameterValue(parameter);
  }
  metrics["scene_parameters"] = parameters;
  nlohmann::json sceneMetrics = nlohmann::json::object();
  for (const scenes::SceneMetric& metric : summary.sceneMetrics) {
    sceneMetrics[metric.name] = metric.value;
  }
  metrics["scene_metrics"] = sceneMetrics;
  metrics["bodies"] = bodiesJson(summary.sceneBodies);
  nlohmann::json series = nlohmann::json::array();
  for (const RunSummary::BodySample& sample : summary.bodySeries) {
    series.push_back({{"time", sample.time}, {"bodies", bodiesJson(sample.bodies)}});
  }
  metrics["bodies_series"] = series;
  nlohmann::json frames = nlohmann::json::array();
  for (const RunSummary::FrameSample& f : summary.frameSeries) {
    frames.push_back({f.time, f.wallMilliseconds, f.granules, f.granulesAsleep});
  }
  metrics["frame_series"] = frames;
  // A scene's series sit beside the run's own numbers, where a plot script looks first; a name
  // the runner already uses would silently replace a number, so it is refused.
  auto addTopLevel = [&](const std::string& key, nlohmann::json value) {
    if (metrics.contains(key)) {
      throw std::logic_error("scene '" + summary.scene + "': series key '" + key +
                             "' is already a key of the metrics");
    }
    metrics[key] = std::move(value);
  };
  for (const scenes::SceneSeries& sceneSeries : summary.sceneSeries) {
    nlohmann::json points = nlohmann::json::array();
    for (const std::array<double, 2>& point : sceneSeries.points) {
      points.push_back({point[0], point[1]});
    }
    addTopLevel(sceneSeries.name, std::move(points));
    for (const scenes::SceneMetric& derived : sceneSeries.derived) {
      addTopLevel(derived.name, derived.value);
    }
  }
  return metrics;
}

void writeMetrics(const std::filesystem::path& path, const nlohmann::json& metrics) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  out << metrics.dump(2) << '\n';
  out.close();
  if (!out) throw std::runtime_error("error while writing '" + path.string() + "'");
}

}  // namespace sandphys::samples
