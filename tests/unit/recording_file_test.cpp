// The recording file (docs/recording.md) without a GPU: what is written is read back bit for bit,
// and every kind of bad file gets an error that names the file and the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>

#include <sandphys/sandphys.h>
#include <zstd.h>

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace sandphys {
namespace {

std::filesystem::path tempFile(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
          name);
}

WorldSnapshot snapshotOf(std::uint64_t frame, std::uint32_t bodies) {
  WorldSnapshot s;
  s.frame = frame;
  s.steps = 100 * frame;
  s.simulatedTime = 1e-3 * double(frame);
  for (std::uint32_t i = 0; i < bodies; ++i) {
    StoredBody b;
    const float f = float(i) + 0.25f * float(frame);
    b.position = {f, -f, 0.5f * f};
    b.principalOrientation = {.w = 0.8f, .x = 0.0f, .y = 0.6f, .z = 0.0f};
    b.velocity = {std::numeric_limits<float>::denorm_min(), -0.0f, 3.0f};
    b.angularVelocity = {1e-30f, 2.0f, -7.5f};
    b.alive = i % 3 != 0;
    s.bodies.push_back(b);
  }
  // With sleep the particles' last forces come along (w: integer words).
  for (std::uint32_t i = 0; i < 2 * bodies; ++i) {
    StoredForces f;
    f.force = {std::bit_cast<std::uint32_t>(-0.0f), std::bit_cast<std::uint32_t>(float(i)),
               std::bit_cast<std::uint32_t>(1e-30f), std::uint32_t(frame + i)};
    f.torque = {std::bit_cast<std::uint32_t>(0.5f * float(i)), 0u, 1u,
                std::bit_cast<std::uint32_t>(float(i % 2))};
    s.forces.push_back(f);
  }
  return s;
}

RecordedFrame frameOf(std::uint64_t index) {
  RecordedFrame f;
  f.frameDt = 1.0f / 60.0f;
  f.steps = 100 * index;
  f.simulatedTime = 1e-3 * double(index);
  f.stateHash = 0x0123456789abcdefull ^ index;
  if (index % 2 == 0) {
    f.inputs.push_back({7, BodyDesc{.position = {1, 2, 3},
                                    .orientation = {0.5f, 0.5f, 0.5f, 0.5f},
                                    .velocity = {-1, 0, 1},
                                    .angularVelocity = {0, 9, 0},
                                    .motion = Motion::Kinematic}});
  }
  f.events = {std::uint8_t(index), 0, 255};
  return f;
}

// Writes 12 frames, a snapshot every 5 and one at the start; returns the file.
std::filesystem::path writeSample(const std::string& name, bool finish = true) {
  const std::filesystem::path file = tempFile(name);
  RecordingWriter writer(file, {{"scene", "box-drop"}, {"param:seed", "7"}, {"empty", ""}});
  writer.addSnapshot(snapshotOf(0, 5));
  for (std::uint64_t i = 1; i <= 12; ++i) {
    writer.addFrame(frameOf(i));
    if (i % 5 == 0) writer.addSnapshot(snapshotOf(i, 5));
  }
  if (finish) writer.finish(2.5);
  return file;
}

std::vector<char> bytesOf(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::filesystem::path& file, const std::vector<char>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// The message of the RecordingError that reading `file` throws (empty when none is thrown).
std::string readError(const std::filesystem::path& file) {
  try {
    (void)readRecording(file);
  } catch (const RecordingError& error) {
    return error.what();
  }
  return {};
}

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Writes `snapshot`, then a plain snapshot of the next frame with as many bodies, to `file`.
void writeSnapshotAndPlainOne(const std::filesystem::path& file, const WorldSnapshot& snapshot) {
  RecordingWriter writer(file, {{"scene", "box-drop"}});
  writer.addSnapshot(snapshot);
  writer.addSnapshot(snapshotOf(snapshot.frame + 1, std::uint32_t(snapshot.bodies.size())));
  writer.finish(1.0);
}

TEST(RecordingFile, ReadsBackWhatWasWrittenBitForBit) {
  const std::filesystem::path file = writeSample("sample.sprec");
  const Recording r = readRecording(file);
  ASSERT_EQ(r.settings.size(), 3u);
  EXPECT_EQ(*r.setting("scene"), "box-drop");
  EXPECT_EQ(*r.setting("param:seed"), "7");
  EXPECT_EQ(*r.setting("empty"), "");
  EXPECT_EQ(r.setting("missing"), nullptr);
  EXPECT_EQ(r.wallSeconds, 2.5);
  EXPECT_EQ(r.bytes, std::filesystem::file_size(file));
  ASSERT_EQ(r.frames.size(), 12u);
  for (std::uint64_t i = 1; i <= 12; ++i) {
    const RecordedFrame expected = frameOf(i);
    const RecordedFrame& got = r.frames[i - 1];
    EXPECT_TRUE(sameBits(got.frameDt, expected.frameDt));
    EXPECT_EQ(got.steps, expected.steps);
    EXPECT_EQ(got.simulatedTime, expected.simulatedTime);
    EXPECT_EQ(got.stateHash, expected.stateHash);
    EXPECT_EQ(got.events, expected.events);
    ASSERT_EQ(got.inputs.size(), expected.inputs.size());
    for (std::size_t k = 0; k < got.inputs.size(); ++k) {
      EXPECT_EQ(got.inputs[k].body, 7u);
      EXPECT_EQ(got.inputs[k].state.motion, Motion::Kinematic);
      EXPECT_TRUE(sameBits(got.inputs[k].state.orientation.z, 0.5f));
      EXPECT_TRUE(sameBits(got.inputs[k].state.angularVelocity.y, 9.0f));
    }
  }
  ASSERT_EQ(r.snapshots.size(), 3u);
  for (const WorldSnapshot& s : r.snapshots) {
    const WorldSnapshot expected = snapshotOf(s.frame, 5);
    EXPECT_EQ(s.steps, expected.steps);
    EXPECT_EQ(s.simulatedTime, expected.simulatedTime);
    EXPECT_FALSE(firstDifference(expected, s)) << firstDifference(expected, s)->describe();
    EXPECT_EQ(stateHash(expected), stateHash(s));
  }
  EXPECT_EQ(r.snapshots[1].frame, 5u);
}

// With rolling friction a snapshot's rolling springs follow it in a record of their own, and
// come back with it bit for bit, named where they differ.
TEST(RecordingFile, RollingSpringsComeBackWithTheirSnapshot) {
  WorldSnapshot snapshot = snapshotOf(3, 2);
  snapshot.contacts.resize(4);
  snapshot.rolling.resize(4);
  for (std::uint32_t i = 0; i < 4; ++i) {
    snapshot.contacts[i].slots[i][3] = i + 10;  // a partner key
    snapshot.rolling[i].springs[i] = {std::bit_cast<std::uint32_t>(1e-7f * float(i + 1)),
                                      std::bit_cast<std::uint32_t>(-0.0f), 1u};
  }
  const std::filesystem::path file = tempFile("rolling.sprec");
  writeSnapshotAndPlainOne(file, snapshot);  // no ROLL record follows the second
  const Recording r = readRecording(file);
  ASSERT_EQ(r.snapshots.size(), 2u);
  EXPECT_FALSE(firstDifference(snapshot, r.snapshots[0]))
      << firstDifference(snapshot, r.snapshots[0])->describe();
  EXPECT_EQ(stateHash(snapshot), stateHash(r.snapshots[0]));
  EXPECT_TRUE(r.snapshots[1].rolling.empty());

  WorldSnapshot changed = snapshot;
  changed.rolling[2].springs[2][1] ^= 1u;
  const std::optional<StateDifference> difference = firstDifference(r.snapshots[0], changed);
  ASSERT_TRUE(difference);
  EXPECT_EQ(difference->body, 2u);
  EXPECT_EQ(difference->field, "contact slot 2 rolling.y");
  EXPECT_NE(stateHash(changed), stateHash(snapshot));

  // Springs that name another frame than the snapshot before them are malformed, by frame.
  std::vector<char> bytes = bytesOf(file);
  const auto at = std::search(bytes.begin(), bytes.end(), "ROLL", std::next("ROLL", 4));
  ASSERT_NE(at, bytes.end());
  ++*(at + 8);  // the record's frame, after its tag and length
  // The end record's checksum made to match, as a writer with this fault would have written it.
  const std::uint64_t checksum = XXH3_64bits(bytes.data(), bytes.size() - 8);
  std::memcpy(bytes.data() + bytes.size() - 8, &checksum, sizeof checksum);
  writeBytes(file, bytes);
  const std::string message = readError(file);
  EXPECT_NE(message.find("is malformed: rolling springs of frame 4 for 4 particles"),
            std::string::npos)
      << message;
}

// Once a sort of the granules by place has moved any, a snapshot carries the id of each slot's
// body (a BIDS record after it); the ids are state: in the hash and named as a difference.
TEST(RecordingFile, BodyIdsComeBackWithTheirSnapshot) {
  WorldSnapshot snapshot = snapshotOf(3, 4);
  snapshot.bodyIds = {2, 0, 3, 1};
  const std::filesystem::path file = tempFile("ids.sprec");
  writeSnapshotAndPlainOne(file, snapshot);  // no BIDS record follows the second
  const Recording r = readRecording(file);
  ASSERT_EQ(r.snapshots.size(), 2u);
  EXPECT_EQ(r.snapshots[0].bodyIds, snapshot.bodyIds);
  EXPECT_EQ(stateHash(snapshot), stateHash(r.snapshots[0]));
  EXPECT_TRUE(r.snapshots[1].bodyIds.empty());

  WorldSnapshot own = snapshot;
  own.bodyIds.clear();  // each slot its own body
  EXPECT_NE(stateHash(own), stateHash(snapshot));
  const std::optional<StateDifference> difference = firstDifference(own, snapshot);
  ASSERT_TRUE(difference);
  EXPECT_EQ(difference->body, 0u);
  EXPECT_EQ(difference->field, "body id");
  EXPECT_EQ(difference->describe(), "body 0 body id: recorded 0, replayed 2");
  // Ids that are every slot's own hash as none.
  WorldSnapshot identity = own;
  identity.bodyIds = {0, 1, 2, 3};
  EXPECT_EQ(stateHash(identity), stateHash(own));
}

TEST(RecordingFile, KeepsThePrincipalOrientationInTheGpusWordOrder) {
  // Four different words, so that any other order shows (the file keeps any bits, unit or not).
  WorldSnapshot snapshot;
  snapshot.bodies.emplace_back().principalOrientation = {
      .w = 0.125f, .x = 0.25f, .y = 0.5f, .z = 0.75f};
  const std::filesystem::path file = tempFile("order.sprec");
  {
    RecordingWriter writer(file, {});
    writer.addSnapshot(snapshot);
    writer.finish(0.0);
  }
  const std::vector<char> bytes = bytesOf(file);
  // The file header (16 bytes), the SETS record (8-byte record header, a count of 0), the SNAP
  // record's header and its 36 bytes of frame, steps, time and counts, then its zstd frame.
  constexpr std::size_t kSnapshotAt = 16 + 12;
  constexpr std::size_t kFrameAt = kSnapshotAt + 8 + 36;
  std::uint32_t payload = 0;
  std::memcpy(&payload, bytes.data() + kSnapshotAt + 4, sizeof payload);
  std::array<float, 14> body{};  // position, orientation, velocity, spin, status
  ASSERT_EQ(ZSTD_decompress(body.data(), sizeof body, bytes.data() + kFrameAt, payload - 36),
            sizeof body);
  EXPECT_EQ(body[3], 0.25f);   // x
  EXPECT_EQ(body[4], 0.5f);    // y
  EXPECT_EQ(body[5], 0.75f);   // z
  EXPECT_EQ(body[6], 0.125f);  // w
  const Quat back = readRecording(file).snapshots.at(0).bodies.at(0).principalOrientation;
  EXPECT_EQ(std::memcmp(&back, &snapshot.bodies[0].principalOrientation, sizeof back), 0);
}

TEST(RecordingFile, ANegativeZeroOrOneBitIsADifferenceNamedWithBothValues) {
  const WorldSnapshot a = snapshotOf(3, 4);
  WorldSnapshot b = a;
  EXPECT_FALSE(firstDifference(a, b));
  EXPECT_EQ(stateHash(a), stateHash(b));
  b.bodies[2].velocity[1] = 0.0f;  // was -0.0f: equal as numbers, not as bits
  const auto d = firstDifference(a, b);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->body, 2u);
  EXPECT_EQ(d->field, "velocity.y");
  EXPECT_NE(stateHash(a), stateHash(b));
  EXPECT_NE(d->describe().find("0x80000000"), std::string::npos) << d->describe();
  EXPECT_NE(d->describe().find("0x00000000"), std::string::npos) << d->describe();

  b = a;
  b.bodies[3].alive = !b.bodies[3].alive;
  ASSERT_TRUE(firstDifference(a, b));
  EXPECT_EQ(firstDifference(a, b)->field, "alive");
  EXPECT_NE(stateHash(a), stateHash(b));

  b = a;
  b.bodies.pop_back();
  ASSERT_TRUE(firstDifference(a, b));
  EXPECT_EQ(firstDifference(a, b)->field, "body count");
}

// The difference `change` makes to `a`, which changes its state hash as well.
StateDifference differenceAfter(const WorldSnapshot& a,
                                const std::function<void(WorldSnapshot&)>& change) {
  WorldSnapshot b = a;
  change(b);
  EXPECT_NE(stateHash(a), stateHash(b));
  const std::optional<StateDifference> difference = firstDifference(a, b);
  EXPECT_TRUE(difference);
  return difference.value_or(StateDifference{});
}

TEST(RecordingFile, AChangedForceIsADifferenceNamedByParticleAndWord) {
  const WorldSnapshot a = snapshotOf(3, 4);
  const StateDifference calm = differenceAfter(a, [](WorldSnapshot& b) { b.forces[5].force[3]++; });
  EXPECT_EQ(calm.describe(), "particle 5 force.w: recorded 8, replayed 9");
  // Was 1.0f: the slots changed.
  const StateDifference slots =
      differenceAfter(a, [](WorldSnapshot& b) { b.forces[5].torque[3] = 0u; });
  EXPECT_EQ(slots.field, "torque.w");
  EXPECT_NE(slots.describe().find("0x3f800000"), std::string::npos) << slots.describe();
  // Was -0.0f.
  EXPECT_EQ(differenceAfter(a, [](WorldSnapshot& b) { b.forces[0].force[0] = 0u; }).field,
            "force.x");
  EXPECT_EQ(differenceAfter(a, [](WorldSnapshot& b) { b.forces.pop_back(); }).field,
            "forces count");
}

TEST(RecordingFile, AMissingFileIsNamed) {
  const std::string message = readError(tempFile("does-not-exist.sprec"));
  EXPECT_NE(message.find("cannot open recording"), std::string::npos) << message;
  EXPECT_NE(message.find("does-not-exist.sprec"), std::string::npos) << message;
}

TEST(RecordingFile, AnotherKindOfFileIsNotARecording) {
  const std::filesystem::path file = tempFile("notes.txt");
  writeBytes(file, {'h', 'e', 'l', 'l', 'o'});
  const std::string message = readError(file);
  EXPECT_NE(message.find("is not a sandphys recording"), std::string::npos) << message;
  EXPECT_NE(message.find("notes.txt"), std::string::npos) << message;
}

TEST(RecordingFile, AnotherFormatVersionIsRefusedWithBothVersions) {
  const std::filesystem::path file = writeSample("v2.sprec");
  std::vector<char> bytes = bytesOf(file);
  const std::uint32_t version = kRecordingVersion + 1;
  std::memcpy(bytes.data() + 12, &version, sizeof version);
  writeBytes(file, bytes);
  const std::string message = readError(file);
  EXPECT_NE(message.find("format version " + std::to_string(version)), std::string::npos)
      << message;
  EXPECT_NE(message.find("reads version " + std::to_string(kRecordingVersion)), std::string::npos)
      << message;
  EXPECT_NE(message.find("v2.sprec"), std::string::npos) << message;
}

TEST(RecordingFile, AnInterruptedRecordingIsTruncatedWhereverItStops) {
  // Never finished: no end record.
  {
    const std::filesystem::path file = writeSample("unfinished.sprec", false);
    const std::string message = readError(file);
    EXPECT_NE(message.find("is truncated"), std::string::npos) << message;
    EXPECT_NE(message.find("12 frames"), std::string::npos) << message;
    EXPECT_NE(message.find("unfinished.sprec"), std::string::npos) << message;
  }
  // Cut at every length from the end of the header to one byte short of the whole.
  const std::filesystem::path whole = writeSample("whole.sprec");
  const std::vector<char> bytes = bytesOf(whole);
  const std::filesystem::path cut = tempFile("cut.sprec");
  for (std::size_t length = 16; length < bytes.size(); length += 7) {
    writeBytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(length)));
    const std::string message = readError(cut);
    EXPECT_NE(message.find("is truncated"), std::string::npos) << length << ": " << message;
  }
}

TEST(RecordingFile, AChangedByteIsReportedAsDamagedByTheChecksum) {
  const std::filesystem::path file = writeSample("damaged.sprec");
  const std::vector<char> original = bytesOf(file);
  // A byte in the settings, in a frame's hash, inside a compressed snapshot, in the end counts.
  for (std::size_t at :
       {std::size_t(30), original.size() / 3, original.size() / 2, original.size() - 30}) {
    std::vector<char> bytes = original;
    bytes[at] = char(bytes[at] ^ 0x10);
    writeBytes(file, bytes);
    const std::string message = readError(file);
    EXPECT_NE(message.find("is damaged: its checksum"), std::string::npos) << at << ": " << message;
    EXPECT_NE(message.find("damaged.sprec"), std::string::npos) << message;
  }
}

TEST(RecordingFile, ADirectoryIsNamedAsOne) {
  const std::filesystem::path folder = tempFile("folder.sprec");
  std::filesystem::create_directories(folder);
  const std::string message = readError(folder);
  EXPECT_NE(message.find("folder.sprec"), std::string::npos) << message;
  EXPECT_NE(message.find("it is a directory"), std::string::npos) << message;
}

TEST(RecordingFile, ASettingGivenTwiceIsMalformedNotADifference) {
  const std::filesystem::path file = tempFile("twice.sprec");
  {
    RecordingWriter writer(file, {{"scene", "box-drop"}, {"param:seed", "7"}, {"param:seed", "8"}});
    writer.finish(0.0);
  }
  const std::string message = readError(file);
  EXPECT_NE(message.find("give 'param:seed' twice"), std::string::npos) << message;
  EXPECT_NE(message.find("twice.sprec"), std::string::npos) << message;
}

TEST(RecordingFile, AFrameDurationNoWorldCouldHaveHadIsMalformed) {
  for (const float frameDt :
       {std::numeric_limits<float>::quiet_NaN(), -0.5f, std::numeric_limits<float>::infinity()}) {
    const std::filesystem::path file = tempFile("duration.sprec");
    {
      RecordingWriter writer(file, {{"scene", "box-drop"}});
      writer.addFrame(frameOf(1));
      RecordedFrame bad = frameOf(2);
      bad.frameDt = frameDt;
      writer.addFrame(bad);
      writer.finish(0.0);
    }
    const std::string message = readError(file);
    EXPECT_NE(message.find("is malformed: frame 1 has frame duration"), std::string::npos)
        << message;
  }
}

TEST(RecordingFile, AnUnwritableFileIsNamed) {
  try {
    RecordingWriter writer(std::filesystem::path("/nonexistent-folder/run.sprec"), {});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent-folder/run.sprec"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace sandphys
