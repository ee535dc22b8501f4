#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sandphys/body.h"
#include "sandphys/snapshot.h"

namespace sandphys {

/// A body state set from outside the sand during a frame (a Bullet bridge's push, a tool): an
/// input of a recording.
struct RecordedInput {
  std::uint32_t body = 0;  ///< the body's id (BodyId::index)
  BodyDesc state;
};

/// Where two inputs first differ, bit for bit: field "body" (the slots differ), a float field of
/// BodyDesc ("position.x" ... "angularVelocity.z", orientation w first) or "motion"; `body` is the
/// recorded input's slot.
std::optional<StateDifference> firstDifference(const RecordedInput& recorded,
                                               const RecordedInput& replayed);

/// One frame of a recording: what went in and a hash of what came out.
struct RecordedFrame {
  float frameDt = 0.0f;               ///< the duration the frame was stepped with, s
  std::uint64_t steps = 0;            ///< World::stepCount after the frame
  double simulatedTime = 0.0;         ///< World::simulatedTime after the frame, s
  std::uint64_t stateHash = 0;        ///< World::readStateHash after the frame
  std::vector<RecordedInput> inputs;  ///< bodies set from outside during the frame, in order
  std::vector<std::uint8_t> events;   ///< the application's own events (opaque to sandphys)
};

/// Version of the recording format this build writes and reads (docs/recording.md).
inline constexpr std::uint32_t kRecordingVersion = 3;

/// A recording as read back: the application's description of the run (scene, parameters,
/// flags, as key and value text in the order written), every frame, and the snapshots in frame
/// order.
struct Recording {
  std::filesystem::path file;
  std::vector<std::pair<std::string, std::string>> settings;
  std::vector<RecordedFrame> frames;
  std::vector<WorldSnapshot> snapshots;
  /// Wall time of the recorded run's frames, s, as the recorder measured it.
  double wallSeconds = 0.0;
  /// Size of the file, bytes.
  std::uint64_t bytes = 0;

  /// The value of setting `key`, or nullptr.
  const std::string* setting(std::string_view key) const;
};

/// Writes a recording as the run goes, so that an interrupted run leaves a file that
/// readRecording reports as truncated. Snapshots are compressed with zstd; the end record holds
/// an XXH3 checksum of everything before it.
class RecordingWriter {
 public:
  /// Creates (or replaces) `file` and writes the header and `settings`. Throws Error naming the
  /// file when it cannot be written.
  RecordingWriter(const std::filesystem::path& file,
                  const std::vector<std::pair<std::string, std::string>>& settings);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  void addFrame(const RecordedFrame& frame);
  void addSnapshot(const WorldSnapshot& snapshot);
  /// Writes the end record (frame and snapshot counts, `wallSeconds`, the checksum) and closes the
  /// file; returns its size in bytes. Throws Error naming the file on a write failure.
  std::uint64_t finish(double wallSeconds);

  std::uint64_t framesWritten() const { return m_frames; }

 private:
  void writeRecord(std::uint32_t tag, const std::vector<std::uint8_t>& payload);
  /// The ROLL record of `snapshot`'s rolling springs.
  void addRolling(const WorldSnapshot& snapshot);

  std::filesystem::path m_file;
  std::ofstream m_out;
  struct Checksum;
  std::unique_ptr<Checksum> m_checksum;
  std::uint64_t m_frames = 0;
  std::uint64_t m_snapshots = 0;
  std::uint64_t m_bytes = 0;
  bool m_finished = false;
};

/// Reads and checks a recording. Throws RecordingError naming the file and the problem: missing
/// or unreadable, not a recording, another format version, truncated (no end record: the run
/// was interrupted), damaged (the checksum does not match) or malformed.
Recording readRecording(const std::filesystem::path& file);

}  // namespace sandphys
