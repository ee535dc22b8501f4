#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "app/golden.h"
#include "app/run.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Frame duration of the recordings the replay tests make: the goldens'.
inline constexpr double kTestFrameDt = kGoldenFrameDt;

/// A recording file in the temporary folder, named after `name`.
std::filesystem::path tempRecording(const std::string& name);

/// Records `frames` frames of `scene` to `file` as sandphys-samples --record does, a snapshot
/// every `snapshotEvery` frames.
RunSummary recordScene(scenes::Scene& scene, const std::filesystem::path& file,
                       std::uint64_t frames, std::uint64_t snapshotEvery);

}  // namespace sandphys::samples
