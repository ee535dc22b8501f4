#include "app/golden.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <variant>

#include "app/metrics.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"

namespace sandphys::samples {

namespace {

using nlohmann::json;

json value(double v, double tolerance) {
  return json{{"value", v}, {"tolerance", tolerance}};
}

// Compares `measured` and `golden` objects of {"value", "tolerance"} under `path`.
void compareValues(const json& measured, const json& golden, const std::string& path,
                   std::vector<std::string>& out) {
  for (const auto& [key, expected] : golden.items()) {
    const std::string name = path + key;
    if (!measured.contains(key)) {
      out.push_back(name + ": in the golden, not measured");
      continue;
    }
    const json& got = measured.at(key);
    if (expected.contains("value")) {
      const double want = expected.at("value").get<double>();
      const double tolerance = expected.at("tolerance").get<double>();
      const double have = got.at("value").get<double>();
      if (!(std::abs(have - want) <= tolerance)) {
        char text[256];
        std::snprintf(text, sizeof text, "%s: measured %.9g, golden %.9g (tolerance %.3g)",
                      name.c_str(), have, want, tolerance);
        out.emplace_back(text);
      }
    } else {
      compareValues(got, expected, name + ".", out);
    }
  }
  for (const auto& [key, ignored] : measured.items()) {
    if (!golden.contains(key)) out.push_back(path + key + ": measured, not in the golden");
  }
}

}  // namespace

std::unique_ptr<scenes::Scene> goldenScene(std::string_view name) {
  const scenes::SceneEntry* entry = scenes::findScene(name);
  if (!entry) throw std::invalid_argument("unknown scene '" + std::string(name) + "'");
  std::unique_ptr<scenes::Scene> scene = entry->create();
  scenes::useTestSize(*scene);
  // The benchmark drops its first batch from 50 d into a cylinder 100 d wide: a fifth of a second
  // would be free fall over a floor of 7800 particles. Low and narrow, it lands within the run.
  if (name == "cylinder-pile") {
    scenes::setSceneParameter(*scene, "first-drop", "3");
    scenes::setSceneParameter(*scene, "radius", "12");
  }
  return scene;
}

json goldenMetrics(const RunSummary& summary, scenes::Scene& scene) {
  const double d = summary.particleDiameter;
  json settings{{"frames", summary.frames}, {"frame_dt", summary.frameDt}};
  json parameters = json::object();
  for (const scenes::SceneParameter& parameter : scene.parameters()) {
    std::string text = scenes::formatSceneParameter(parameter);
    // A file (rock-drop's mesh) by its name: the folder differs between clones.
    if (std::holds_alternative<std::string*>(parameter.value)) {
      text = std::filesystem::path(text).filename().string();
    }
    parameters[parameter.name] = text;
  }
  settings["parameters"] = parameters;

  json metrics;
  metrics["granules_alive"] = value(summary.stats.granulesAlive, 0.0);
  metrics["steps"] = value(double(summary.stats.steps), 0.0);
  metrics["simulated_seconds"] = value(summary.stats.simulatedTime, 1e-9);
  metrics["contacts"] = value(summary.stats.contacts, 2.0 + 0.05 * summary.stats.contacts);
  metrics["kinetic_energy_j"] =
      value(summary.stats.kineticEnergy, 1e-6 + 0.1 * summary.stats.kineticEnergy);
  double sum[3] = {0.0, 0.0, 0.0};
  std::uint32_t granules = 0;
  for (const BodyState& body : summary.bodies) {
    if (!body.alive || !body.granule) continue;
    sum[0] += body.position.x;
    sum[1] += body.position.y;
    sum[2] += body.position.z;
    ++granules;
  }
  if (granules > 0) {
    metrics["sand_centre_m"] = {{"x", value(sum[0] / granules, 0.25 * d)},
                                {"y", value(sum[1] / granules, 0.25 * d)},
                                {"z", value(sum[2] / granules, 0.25 * d)}};
  }
  json bodies = json::object();
  for (const scenes::SceneBody& body : summary.sceneBodies) {
    bodies[body.name] = {{"x", value(body.position.x, 0.25 * d)},
                         {"y", value(body.position.y, 0.25 * d)},
                         {"z", value(body.position.z, 0.25 * d)},
                         {"tilt_deg", value(body.tiltDegrees, 2.0)}};
  }
  if (!bodies.empty()) metrics["bodies"] = bodies;
  return json{{"scene", summary.scene}, {"settings", settings}, {"metrics", metrics}};
}

std::vector<std::string> compareWithGolden(const json& measured, const json& golden) {
  std::vector<std::string> out;
  if (measured.at("scene") != golden.at("scene")) {
    out.push_back("scene: measured " + measured.at("scene").dump() + ", golden " +
                  golden.at("scene").dump());
    return out;
  }
  if (measured.at("settings") != golden.at("settings")) {
    out.push_back("settings: measured " + measured.at("settings").dump() + ", golden " +
                  golden.at("settings").dump() +
                  " (the golden was made for other settings; regenerate it on purpose)");
    return out;
  }
  compareValues(measured.at("metrics"), golden.at("metrics"), "", out);
  return out;
}

int writeGoldens(const std::filesystem::path& directory, bool quiet) {
  std::filesystem::create_directories(directory);
  const GpuContext gpu = GpuContext::headless();
  for (const scenes::SceneEntry& entry : scenes::sceneRegistry()) {
    std::unique_ptr<scenes::Scene> scene = goldenScene(entry.name);
    ProgressLine progress(false);
    const RunSummary summary =
        runScene(gpu, *scene, kGoldenFrames, kGoldenFrameDt, false, progress);
    const std::filesystem::path file = directory / (std::string(entry.name) + ".json");
    writeMetrics(file, goldenMetrics(summary, *scene));
    if (!quiet) {
      std::fprintf(stderr, "sandphys-samples: wrote %s (%llu frames, %.2f s wall)\n",
                   file.string().c_str(), static_cast<unsigned long long>(summary.frames),
                   summary.wallSeconds);
    }
  }
  return 0;
}

}  // namespace sandphys::samples
