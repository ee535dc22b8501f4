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

namespace sandphys {

/// One body slot exactly as the GPU stores it: the bits World::readStateHash covers.
struct StoredBody {
  std::array<float, 3> position{};         ///< centre of mass, m
  std::array<float, 4> orientation{};      ///< x, y, z, w of the principal frame's orientation
  std::array<float, 3> velocity{};         ///< m/s
  std::array<float, 3> angularVelocity{};  ///< rad/s, world frame
  bool alive = true;                       ///< false once a sink removed it
  /// Calm count (WorldSettings::sleep, docs/architecture.md "sleep"): asleep at
  /// SleepModel::substeps; always 0 without sleep. Below 2^30.
  std::uint32_t calm = 0;
};

/// The one word the state hash and recordings keep of a StoredBody's alive flag and calm count:
/// bit 0 alive, the calm count above it (so 1 or 0 without sleep).
inline std::uint32_t statusWord(const StoredBody& b) {
  return (b.alive ? 1u : 0u) | (b.calm << 1);
}

/// Contact slots each particle owns under ContactLaw::HertzMindlin (docs/architecture.md,
/// "contacts"): contacts beyond these get no history and are counted.
inline constexpr std::uint32_t kContactSlots = 12;

/// One particle's contact history exactly as the GPU stores it (ContactLaw::HertzMindlin): each
/// slot's tangential spring (x, y, z as float bits) and partner key, the pair counts of its slots
/// (one byte per slot in pairs[0..2]) and the number of slots in use (pairs[3]). What a contact
/// carries from one substep to the next.
struct StoredContacts {
  std::array<std::array<std::uint32_t, 4>, kContactSlots> slots{};
  std::array<std::uint32_t, 4> pairs{};
};

/// Every body slot in use at one moment (World::readSnapshot, a sync point).
struct WorldSnapshot {
  std::uint64_t frame = 0;     ///< frames run when it was taken (the caller's count; 0 = built)
  std::uint64_t steps = 0;     ///< World::stepCount
  double simulatedTime = 0.0;  ///< World::simulatedTime, s
  /// Frame time World::step had not yet run as a substep (its accumulator), s. Kept so that a
  /// World restored to a snapshot of its own takes its next frame as it would have; recordings
  /// do not store it (read back, it is 0).
  double unsteppedTime = 0.0;
  std::vector<StoredBody> bodies;
  /// Under ContactLaw::HertzMindlin, every particle slot in use; empty under PaperViscous (whose
  /// contacts keep nothing).
  std::vector<StoredContacts> contacts;
};

/// The hash World::readStateHash computes on the GPU, computed here on the CPU from the same bits
/// (docs/recording.md gives the function). For tests and tools.
std::uint64_t stateHash(const WorldSnapshot& snapshot);

/// Where two states first differ: the lowest body slot, then the first field in the order of
/// StoredBody ("position.x" ... "angularVelocity.z", "alive", "calm"); field "body count" when the
/// number of slots differs (body is then the smaller count). Then the contact history: the
/// lowest particle (subject Particle), "contact slot K spring.x" ... "contact slot K key",
/// "contact pairs W", or "particle count". Also for inputs (below).
struct StateDifference {
  enum class Subject { Body, Particle };
  std::uint32_t body = 0;  ///< body slot, or particle index when subject is Particle
  std::string field;
  double recorded = 0.0;
  double replayed = 0.0;
  Subject subject = Subject::Body;
  bool integer = false;  ///< the values are integers (keys, counts), not floats
  /// "body 17 velocity.y: recorded 0.123456791 (0x3dfcd6e9), replayed 0.123456798 (0x3dfcd6ea)";
  /// float fields with their bits.
  std::string describe() const;
};
std::optional<StateDifference> firstDifference(const WorldSnapshot& recorded,
                                               const WorldSnapshot& replayed);

/// A body state set from outside the sand during a frame (a Bullet bridge's push, a tool): an
/// input of a recording.
struct RecordedInput {
  std::uint32_t body = 0;  ///< body slot (BodyId::index)
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
inline constexpr std::uint32_t kRecordingVersion = 2;

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
