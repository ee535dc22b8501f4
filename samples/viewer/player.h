#pragma once

#include <filesystem>

#include <sandphys/sandphys.h>

#include "app/playback.h"
#include "viewer/frame_pacer.h"
#include "viewer/frame_stats.h"

namespace sandphys::viewer {

/// --play in the window: a recording's Playback (app/playback.h) moved on once per viewer frame,
/// with a frame pacer for the render quality and the time a catch-up may take per frame.
class Player {
 public:
  /// Reads `file` and builds its scene. Throws RecordingError naming the file when it cannot be
  /// read or this build cannot make what it records.
  Player(const GpuContext& gpu, const std::filesystem::path& file, FramePacer pacer);

  /// One viewer frame. Playing (or `step`), the next recorded frame is re-simulated; else the
  /// re-simulation works towards a frame scrubbed to, for up to the pacer's budget (at least one
  /// frame). Fills `stats` when a frame was stepped.
  void frame(bool playing, bool step, FrameStats& stats);
  /// The last frame is shown and nothing is left to re-simulate.
  bool atEnd() const;

  const std::filesystem::path& file() const { return m_file; }
  samples::Playback& playback() { return m_playback; }
  const samples::Playback& playback() const { return m_playback; }
  FramePacer& pacer() { return m_pacer; }
  const FramePacer& pacer() const { return m_pacer; }
  World& world() { return m_playback.world(); }
  const World& world() const { return m_playback.world(); }
  const scenes::Scene& scene() const { return m_playback.scene(); }

 private:
  std::filesystem::path m_file;
  samples::Playback m_playback;
  FramePacer m_pacer;
};

}  // namespace sandphys::viewer
