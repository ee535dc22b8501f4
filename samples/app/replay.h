#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <sandphys/sandphys.h>

#include "app/recording.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Makes the scene a recording was made of, with its parameters. Throws RecordingError naming the
/// file when the scene no longer exists or the current build refuses a setting. (The World's
/// settings are the recording's "world:" values, which replayRecording applies.)
std::unique_ptr<scenes::Scene> sceneFromRecording(const Recording& recording);

/// What a replay found.
struct ReplayResult {
  std::uint64_t frames = 0;  ///< frames replayed (all of the recording's when identical)
  bool identical = true;
  /// First frame that differs (1 = the first frame; 0 = the state right after build).
  std::uint64_t firstDifferentFrame = 0;
  /// What differs, in words: the quantity, the body or input, the field and both values.
  std::string difference;
  double wallSeconds = 0.0;  ///< wall time of the replayed frames, hash and checks included, s
};

/// Called by replayRecording after each frame's step and update, before the frame is checked
/// (tests perturb the state here).
using ReplayHook = std::function<void(World& world, std::uint64_t frame)>;

/// Re-simulates `recording` headless on `gpu` and checks every frame: step count and simulated
/// time, external inputs, state hash, and every snapshot in full. Stops at the first difference
/// and names it; with a hash difference the body and field come from the snapshot of that frame or
/// the next one. Throws RecordingError (see sceneFromRecording).
ReplayResult replayRecording(const GpuContext& gpu, const Recording& recording,
                             const ReplayHook& afterFrame = {});

/// --replay FILE: reads, replays and reports; returns the exit code (kExitOk when identical).
int runReplay(const std::filesystem::path& file, bool quiet);

}  // namespace sandphys::samples
