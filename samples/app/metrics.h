#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "app/run.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// The metrics of a run as JSON (keys and units in docs: scene, granules, particles, bodies,
/// steps, simulated_seconds, wall_seconds, cundall_number, seconds_simulated_per_wall_second,
/// contacts, kinetic_energy (J), max_overlap_d, penetration_clamps, velocity_clamps,
/// granules_spawned, granules_killed, granules_lost, time_step (s), gpu, scene_parameters,
/// scene_metrics, ...).
nlohmann::json metricsJson(const RunSummary& summary, scenes::Scene& scene);

/// Writes `metrics` to `path`, pretty-printed. Throws std::runtime_error naming the path.
void writeMetrics(const std::filesystem::path& path, const nlohmann::json& metrics);

}  // namespace sandphys::samples
