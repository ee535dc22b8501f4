#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "app/sand_tools.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Keys of a recording's settings (docs/recording.md): scene parameters are "param:NAME", World
/// settings "world:NAME", and "tools" names the viewer's tools when they were attached.
inline constexpr const char* kParameterPrefix = "param:";
inline constexpr const char* kWorldPrefix = "world:";
inline constexpr const char* kToolsKey = "tools";
inline constexpr const char* kSandTools = "sand-tools";

/// Frames between two full snapshots of a recording by default (one a second at 60 frames per
/// second); a replay that finds a difference names the body and field at the next snapshot.
inline constexpr std::uint64_t kDefaultSnapshotEvery = 60;

/// Records a run of a scene (--record FILE): its name, parameters and run flags, and per frame the
/// frame's duration, the scene's external inputs (Scene::externalInputs) and the state hash; a
/// full snapshot after build, every `snapshotEvery` frames and at the end.
class SceneRecorder {
 public:
  /// Creates `file` and writes the settings: `scene`'s name and parameters (as they are now),
  /// `world`, the settings of the World it runs in (which a replay builds its World from),
  /// `frameDt`, `snapshotEvery` and `device` (GpuContext::description). Throws sandphys::Error
  /// naming the file when it cannot be written.
  /// `sandTools`: the run has the viewer's sand tools attached (samples::SandTools), whose input
  /// each frame's events hold (toolEvents) and a replay applies.
  SceneRecorder(const std::filesystem::path& file, scenes::Scene& scene, const WorldSettings& world,
                double frameDt, std::uint64_t snapshotEvery, const std::string& device,
                bool sandTools = false);

  /// After Scene::build: the snapshot of frame 0.
  void begin(World& world);
  /// After frame `frame` (1 = the first) was stepped with `frameDt` and the scene updated;
  /// `events` are the frame's tool input (toolEvents), empty without tools.
  void recordFrame(World& world, const scenes::Scene& scene, float frameDt, std::uint64_t frame,
                   const std::vector<std::uint8_t>& events = {});
  /// The last snapshot (unless the last frame had one) and the end record with the wall time of
  /// the frames since begin() (the recorder's own time left out); returns the file's size, bytes.
  std::uint64_t finish(World& world);

  std::uint64_t frames() const { return m_frames; }
  /// Wall time spent recording (hashes, snapshots, writing), s.
  double ownSeconds() const { return m_ownSeconds; }

 private:
  RecordingWriter m_writer;
  std::uint64_t m_snapshotEvery;
  std::uint64_t m_frames = 0;
  std::uint64_t m_lastSnapshot = 0;
  std::chrono::steady_clock::time_point m_start;
  double m_ownSeconds = 0.0;
};

/// The sand tools' input of one frame as a recording's events: nothing when no tool is held (the
/// cursor does not matter then); else a byte of flags (1 pour, 2 push) and the cursor ray, origin
/// and direction, 6 floats.
std::vector<std::uint8_t> toolEvents(bool pour, bool push, const samples::Ray& cursor);

/// What toolEvents wrote.
struct ToolInput {
  bool pour = false;
  bool push = false;
  samples::Ray cursor;
};
/// Reads toolEvents' bytes of frame `frame` of `recording`. Throws RecordingError naming the file
/// and the frame when they are not.
ToolInput readToolEvents(const Recording& recording, std::uint64_t frame);

/// `settings` with every "world:" value of `recording` in place: a replay's World is the one the
/// recorded run had (the viewer's edits, capacities), whatever the scene's defaults have become
/// since. Throws RecordingError naming the key for one this build does not know or cannot read.
WorldSettings worldSettingsFrom(const Recording& recording, WorldSettings settings);

}  // namespace sandphys::samples
