#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <sandphys/sandphys.h>

#include "app/recording.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Makes the scene a recording was made of, with its parameters. Throws RecordingError naming the
/// file when the scene no longer exists or the current build refuses a setting. (The World's
/// settings are the recording's "world:" values, which replayRecording applies.)
std::unique_ptr<scenes::Scene> sceneFromRecording(const Recording& recording);

/// A recording's scene re-simulated as it ran: the scene and its World built from the recording's
/// settings (worldSettingsFrom), the sand tools attached when the run had them, and each frame
/// stepped with its recorded duration and tool input. --replay and the viewer's --play both run
/// one.
class ReplayRun {
 public:
  /// Builds the scene on a fresh World on `gpu` (frame 0). `recording` must outlive the run.
  /// Throws RecordingError naming the file when this build cannot make what it records (see
  /// sceneFromRecording), GpuError when the World cannot be made.
  ReplayRun(const GpuContext& gpu, const Recording& recording);

  /// Steps the next recorded frame, frame() + 1, which must exist. Throws RecordingError when its
  /// events are not the tools' (or the run had none).
  StepReport stepFrame();

  /// How the state right after build (frame 0) or the frame just stepped differs from the
  /// recording: the substeps run and the simulated time, each external input, the state hash,
  /// and the frame's snapshot when it has one. `hashOnly`: only the hash differs and the frame
  /// has no snapshot to name the body and field.
  struct Difference {
    std::string what;
    bool hashOnly = false;
  };
  std::optional<Difference> checkFrame();
  /// How the state now differs from `snapshot`: the first body and field, or nullopt.
  std::optional<std::string> compareWith(const WorldSnapshot& snapshot) const;

  /// Frames stepped since build.
  std::uint64_t frame() const { return m_frame; }
  World& world() { return *m_world; }
  const World& world() const { return *m_world; }
  scenes::Scene& scene() { return *m_scene; }
  const scenes::Scene& scene() const { return *m_scene; }

 private:
  const Recording& m_recording;
  std::unique_ptr<scenes::Scene> m_scene;
  std::optional<World> m_world;
  std::optional<samples::SandTools> m_tools;
  std::uint64_t m_frame = 0;
};

/// The snapshot `recording` holds of frame `frame`, or null.
const WorldSnapshot* snapshotAt(const Recording& recording, std::uint64_t frame);

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

/// Re-simulates `recording` headless on `gpu` (a ReplayRun) and checks every frame. Stops at the
/// first difference and names it; with a hash difference the body and field come from the
/// snapshot of that frame or the next one. Throws RecordingError (see ReplayRun).
ReplayResult replayRecording(const GpuContext& gpu, const Recording& recording,
                             const ReplayHook& afterFrame = {});

/// When a replay on `gpu` of a recording made on another device differs, why that may be.
std::string deviceCaveat(const GpuContext& gpu, const Recording& recording);

/// --replay FILE: reads, replays and reports; returns the exit code (kExitOk when identical).
int runReplay(const std::filesystem::path& file, bool quiet);

}  // namespace sandphys::samples
