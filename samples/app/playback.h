#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <sandphys/sandphys.h>

#include "app/replay.h"

namespace sandphys::samples {

/// A recording shown frame by frame on a timeline (the viewer's --play). The frames are
/// re-simulated in order, as --replay does, and each is checked against the recording. The
/// timeline moves at once to a recorded snapshot whose bodies the World has (all of them, back
/// from the furthest frame re-simulated; ahead of it, those of scenes that add no bodies on the
/// way), and elsewhere by re-simulating.
///
/// Only the re-simulated state can go on: a scene's own state (its batch counter, a Bullet world)
/// is not in a snapshot. So going on from a snapshot behind re-simulates from the start up to it,
/// going on from one ahead re-simulates from the furthest frame, and coming back to the furthest
/// frame re-simulated puts the World's own state of that frame back.
class Playback {
 public:
  /// Builds the recording's scene (frame 0). Throws RecordingError naming the file when this
  /// build cannot make what it records, GpuError when the World cannot be made.
  Playback(const GpuContext& gpu, Recording recording);
  // The run keeps a reference to the recording.
  Playback(const Playback&) = delete;
  Playback& operator=(const Playback&) = delete;

  const Recording& recording() const { return m_recording; }
  /// Frames the recording holds.
  std::uint64_t frames() const { return m_recording.frames.size(); }
  /// Frame the World shows (0 = right after build).
  std::uint64_t shownFrame() const { return m_shown; }
  /// Frames re-simulated since the last build: the furthest frame that can go on.
  std::uint64_t simulatedFrame() const { return m_run->frame(); }
  /// The World shows a recorded snapshot, not the re-simulated state.
  bool showingSnapshot() const { return m_aside.has_value(); }
  /// Frame being re-simulated towards (advance), or the shown one when there is nothing to do.
  std::uint64_t target() const { return m_target; }
  /// Frames are left to re-simulate before the target is shown.
  bool busy() const { return m_rebuild || (!m_aside && m_run->frame() < m_target); }

  /// Shows frame `frame` (clamped to the recording): the furthest re-simulated frame at once; any
  /// other at once as the latest recorded snapshot at or before it whose bodies the World has,
  /// unless a later frame than the furthest has none beyond it: then once advance() has
  /// re-simulated up to it.
  void scrubTo(std::uint64_t frame);
  /// Goes on `count` frames from the frame shown, re-simulated (advance). From a snapshot behind
  /// the furthest frame re-simulated, the scene is built again and re-simulated up to it first.
  void playOn(std::uint64_t count = 1);
  /// The recorded snapshot frames before and after the frame shown (for keys that jump), or
  /// nullopt when there is none.
  std::optional<std::uint64_t> snapshotBefore() const;
  std::optional<std::uint64_t> snapshotAfter() const;

  /// Re-simulates towards the target, checking every frame, for up to `budgetMilliseconds` of
  /// wall time (at least one frame when there is one to do). Returns the report of the last frame
  /// stepped, or nullopt when none was.
  std::optional<StepReport> advance(double budgetMilliseconds);

  /// The first frame whose re-simulation differed from the recording, and how.
  struct Mismatch {
    std::uint64_t frame = 0;
    std::string what;
  };
  /// nullopt while every frame re-simulated matched the recording.
  const std::optional<Mismatch>& mismatch() const { return m_mismatch; }
  /// Frames re-simulated and checked since the start, rebuilds counted once (the furthest).
  std::uint64_t checkedFrames() const { return m_checked; }

  World& world() { return m_run->world(); }
  const World& world() const { return m_run->world(); }
  const scenes::Scene& scene() const { return m_run->scene(); }

 private:
  const GpuContext& m_gpu;
  Recording m_recording;
  std::unique_ptr<ReplayRun> m_run;
  // The re-simulated state, put aside while a recorded snapshot is shown.
  std::optional<WorldSnapshot> m_aside;
  std::optional<Mismatch> m_mismatch;
  std::uint64_t m_shown = 0;
  std::uint64_t m_target = 0;
  std::uint64_t m_checked = 0;
  bool m_rebuild = false;

  void check();
  void putBack();
};

}  // namespace sandphys::samples
