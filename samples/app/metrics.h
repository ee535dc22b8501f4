#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "app/run.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// The metrics of a run as JSON (keys and units in docs: scene, granules, particles, body_slots,
/// steps, simulated_seconds, wall_seconds, cundall_number, seconds_simulated_per_wall_second,
/// contacts, kinetic_energy (J), max_overlap_d, penetration_clamps, velocity_clamps,
/// granules_spawned, granules_killed, granules_lost, time_step (s), gpu, scene_parameters,
/// scene_metrics, bodies: the scene's rigid bodies that are not sand at the end, each with name,
/// position (m), orientation (w, x, y, z), speed (m/s) and tilt_deg; bodies_series: the same
/// every kBodySeriesFrames frames with its time (s); frame_series: per frame with statistics,
/// [simulated time (s), wall ms, granules, granules asleep], ...), and at the top level each of the
/// scene's series (Scene::series) as a list of [x, y] pairs under its name, with the numbers
/// derived from it under theirs. Throws std::logic_error when a series' key is already taken.
nlohmann::json metricsJson(const RunSummary& summary, scenes::Scene& scene);

/// Writes `metrics` to `path`, pretty-printed. Throws std::runtime_error naming the path.
void writeMetrics(const std::filesystem::path& path, const nlohmann::json& metrics);

}  // namespace sandphys::samples
