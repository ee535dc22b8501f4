#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/run.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Frames of a golden run, and their duration (s): a fifth of a second, short enough for CI.
inline constexpr std::uint64_t kGoldenFrames = 12;
inline constexpr double kGoldenFrameDt = 1.0 / 60.0;

/// The scene `name` at the size of the golden runs and the scene tests: blocks, batches, berms and
/// beds of 4 × 2 × 4 granules, 32 granules where a scene counts them, 2 layers; its geometry and
/// everything else as registered, but for the cylinder pile's drop height (3 d) and radius (12 d),
/// so that its batch lands within the run. Throws std::invalid_argument for an unknown name.
std::unique_ptr<scenes::Scene> goldenScene(std::string_view name);

/// The headline metrics of a run and the tolerance each must keep against its golden, as the
/// golden file holds them (tests/golden/<scene>.json): granules alive and substeps exactly; the
/// simulated time; contacts (within 5% and 2); kinetic energy (within 10% and 1 µJ); the sand's
/// centre of mass (within d/4 on each axis); each of the scene's bodies: position (within d/4)
/// and tilt (within 2 degrees). Also the scene's parameters and the run's frames, so that a golden
/// made for other settings is noticed.
nlohmann::json goldenMetrics(const RunSummary& summary, scenes::Scene& scene);

/// Where `measured` (from goldenMetrics) leaves `golden`: one line per value outside its
/// tolerance, naming the key and both values, or per setting that differs; empty when it keeps
/// to all of them.
std::vector<std::string> compareWithGolden(const nlohmann::json& measured,
                                           const nlohmann::json& golden);

/// Runs every registered scene at its golden size and writes `directory`/<scene>.json
/// (sandphys-samples --write-goldens DIR, see docs/recording.md). The only writer of goldens; tests
/// read them. Returns the exit code.
int writeGoldens(const std::filesystem::path& directory, bool quiet);

}  // namespace sandphys::samples
