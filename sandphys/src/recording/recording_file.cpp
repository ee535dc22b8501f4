// The recording file (docs/recording.md): a header, then records of (tag, length, payload), all
// little-endian; snapshots compressed with zstd; an end record with an XXH3 checksum of every
// byte before it. Written as the run goes, so an interrupted run leaves a truncated file.
#include <array>
#include <bit>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <system_error>

#include <zstd.h>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "core/assert.h"
#include "sandphys/error.h"
#include "sandphys/recording.h"
#include "sandphys/settings.h"

namespace sandphys {

static_assert(std::endian::native == std::endian::little,
              "the recording format is little-endian and written with memcpy");

namespace {

constexpr char kMagic[12] = {'S', 'A', 'N', 'D', 'P', 'H', 'Y', 'S', 'R', 'E', 'C', '\0'};
constexpr std::size_t kFileHeaderBytes = sizeof kMagic + 4;
constexpr std::size_t kRecordHeaderBytes = 8;
constexpr std::size_t kEndPayloadBytes = 32;
constexpr std::size_t kSnapshotBodyBytes = 14 * 4;
constexpr std::size_t kSnapshotContactBytes = sizeof(StoredContacts);
static_assert(sizeof(StoredContacts) == (4 * kContactSlots + 4) * 4);
constexpr std::size_t kSnapshotRollingBytes = sizeof(StoredRolling);
static_assert(sizeof(StoredRolling) == 3 * kContactSlots * 4);
constexpr std::size_t kSnapshotForceBytes = sizeof(StoredForces);
static_assert(sizeof(StoredForces) == 8 * 4);
// Fast and still about halves float state; recordings are written while a scene runs.
constexpr int kZstdLevel = 3;

constexpr std::uint32_t tag(const char (&text)[5]) {
  return std::uint32_t(std::uint8_t(text[0])) | std::uint32_t(std::uint8_t(text[1])) << 8 |
         std::uint32_t(std::uint8_t(text[2])) << 16 | std::uint32_t(std::uint8_t(text[3])) << 24;
}
constexpr std::uint32_t kSettingsTag = tag("SETS");
constexpr std::uint32_t kFrameTag = tag("FRAM");
constexpr std::uint32_t kSnapshotTag = tag("SNAP");
// The rolling springs of the snapshot just before it (rolling friction only), so that a recording
// without rolling friction is laid out as before rolling friction kept state.
constexpr std::uint32_t kRollingTag = tag("ROLL");
// The body ids of the snapshot just before it, once a sort of the granules by place moved any
// (WorldSettings::sortInterval), so that a recording without sorts is laid out as before.
constexpr std::uint32_t kBodyIdsTag = tag("BIDS");
constexpr std::uint32_t kEndTag = tag("END!");

std::string tagText(std::uint32_t value) {
  std::string text;
  for (int i = 0; i < 4; ++i) {
    const char c = char((value >> (8 * i)) & 0xffu);
    text += (c >= 32 && c < 127) ? c : '?';
  }
  return text;
}

std::string hex(std::uint64_t value) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, value);
  return text;
}

class Bytes {
 public:
  template <typename T>
  void put(T value) {
    putRaw(&value, sizeof(T));
  }
  void putText(const std::string& text) {
    put(std::uint32_t(text.size()));
    putRaw(text.data(), text.size());
  }
  void putRaw(const void* data, std::size_t size) {
    if (size == 0) return;
    const std::size_t at = m_data.size();
    m_data.resize(at + size);
    std::memcpy(m_data.data() + at, data, size);
  }
  std::vector<std::uint8_t>& data() { return m_data; }

 private:
  std::vector<std::uint8_t> m_data;
};

// Reads a payload; running past its end is a malformed record.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size, const std::string& context)
      : m_data(data), m_size(size), m_context(context) {}

  template <typename T>
  T get() {
    require(sizeof(T));
    T value;
    std::memcpy(&value, m_data + m_offset, sizeof(T));
    m_offset += sizeof(T);
    return value;
  }
  std::string getText() {
    const std::uint32_t length = get<std::uint32_t>();
    require(length);
    std::string text(reinterpret_cast<const char*>(m_data + m_offset), length);
    m_offset += length;
    return text;
  }
  const std::uint8_t* take(std::size_t size) {
    require(size);
    const std::uint8_t* p = m_data + m_offset;
    m_offset += size;
    return p;
  }
  std::size_t remaining() const { return m_size - m_offset; }

 private:
  void require(std::size_t size) const {
    if (size > m_size - m_offset) {
      throw RecordingError(m_context + " is malformed: a field runs past the end of its record");
    }
  }
  const std::uint8_t* m_data;
  std::size_t m_size;
  std::size_t m_offset = 0;
  const std::string& m_context;
};

void putBodyDesc(Bytes& out, const BodyDesc& d) {
  for (float v : {d.position.x, d.position.y, d.position.z, d.orientation.w, d.orientation.x,
                  d.orientation.y, d.orientation.z, d.velocity.x, d.velocity.y, d.velocity.z,
                  d.angularVelocity.x, d.angularVelocity.y, d.angularVelocity.z}) {
    out.put(v);
  }
  out.put(std::uint32_t(d.motion));
}

BodyDesc getBodyDesc(Reader& in) {
  BodyDesc d;
  float v[13];
  for (float& x : v) x = in.get<float>();
  d.position = {v[0], v[1], v[2]};
  d.orientation = {v[3], v[4], v[5], v[6]};
  d.velocity = {v[7], v[8], v[9]};
  d.angularVelocity = {v[10], v[11], v[12]};
  d.motion = static_cast<Motion>(in.get<std::uint32_t>());
  return d;
}

// A frame's values that no World could have written are refused here, naming the frame, so
// that a replay never reports them as a difference of the simulation.
RecordedFrame readFrame(Reader& in, const std::string& context, std::size_t index) {
  RecordedFrame frame;
  frame.frameDt = in.get<float>();
  frame.steps = in.get<std::uint64_t>();
  frame.simulatedTime = in.get<double>();
  const auto invalid = [&](const std::string& field, double value, const char* limit) {
    std::ostringstream text;
    text << context << " is malformed: frame " << index << " has " << field << " = " << value
         << " (" << limit << ")";
    throw RecordingError(text.str());
  };
  if (!std::isfinite(frame.frameDt) || frame.frameDt < 0.0f) {
    invalid("frame duration", frame.frameDt, "must be finite and >= 0 s");
  }
  if (!std::isfinite(frame.simulatedTime) || frame.simulatedTime < 0.0) {
    invalid("simulated time", frame.simulatedTime, "must be finite and >= 0 s");
  }
  frame.stateHash = in.get<std::uint64_t>();
  const std::uint32_t inputs = in.get<std::uint32_t>();
  for (std::uint32_t i = 0; i < inputs; ++i) {
    RecordedInput input;
    input.body = in.get<std::uint32_t>();
    input.state = getBodyDesc(in);
    frame.inputs.push_back(input);
  }
  const std::uint32_t events = in.get<std::uint32_t>();
  const std::uint8_t* p = in.take(events);
  frame.events.assign(p, p + events);
  return frame;
}

// Appends `raw` as one zstd frame (for recording `file`'s error).
void putCompressed(Bytes& out, const std::vector<std::uint8_t>& raw,
                   const std::filesystem::path& file) {
  std::vector<std::uint8_t> compressed(ZSTD_compressBound(raw.size()));
  const std::size_t size =
      ZSTD_compress(compressed.data(), compressed.size(), raw.data(), raw.size(), kZstdLevel);
  if (ZSTD_isError(size)) {
    throw Error("cannot write recording '" + file.string() + "': zstd: " + ZSTD_getErrorName(size));
  }
  out.putRaw(compressed.data(), size);
}

// The rest of `in`, a zstd frame of rawSize bytes; `what` it is and what it should `hold`, for
// the error.
std::vector<std::uint8_t> decompressRest(Reader& in, std::size_t rawSize,
                                         const std::string& context, const std::string& what,
                                         const std::string& hold) {
  const std::size_t compressedSize = in.remaining();
  const std::uint8_t* compressed = in.take(compressedSize);
  const unsigned long long contentSize = ZSTD_getFrameContentSize(compressed, compressedSize);
  if (contentSize != rawSize) {
    throw RecordingError(context + " is malformed: " + what + " does not hold " + hold);
  }
  std::vector<std::uint8_t> raw(rawSize);
  const std::size_t result = ZSTD_decompress(raw.data(), raw.size(), compressed, compressedSize);
  if (ZSTD_isError(result) || result != rawSize) {
    throw RecordingError(context + " is malformed: " + what + " does not decompress (" +
                         (ZSTD_isError(result) ? ZSTD_getErrorName(result) : "short") + ")");
  }
  return raw;
}

// A ROLL record: the rolling springs of `snapshot`, the one read just before it.
void readRolling(Reader& in, const std::string& context, WorldSnapshot* snapshot) {
  const auto frame = in.get<std::uint64_t>();
  const std::uint32_t particles = in.get<std::uint32_t>();
  if (!snapshot || snapshot->frame != frame || !snapshot->rolling.empty() ||
      particles != snapshot->contacts.size()) {
    throw RecordingError(context + " is malformed: rolling springs of frame " +
                         std::to_string(frame) + " for " + std::to_string(particles) +
                         " particles do not follow that frame's snapshot of as many particles");
  }
  const std::vector<std::uint8_t> raw =
      decompressRest(in, std::size_t(particles) * kSnapshotRollingBytes, context,
                     "the rolling springs of frame " + std::to_string(frame),
                     std::to_string(particles) + " particles'");
  Reader words(raw.data(), raw.size(), context);
  snapshot->rolling.resize(particles);
  for (StoredRolling& r : snapshot->rolling) {
    for (auto& spring : r.springs) {
      for (std::uint32_t& word : spring) word = words.get<std::uint32_t>();
    }
  }
}

// A BIDS record: the body ids of `snapshot`, the one read just before it.
void readBodyIds(Reader& in, const std::string& context, WorldSnapshot* snapshot) {
  const auto frame = in.get<std::uint64_t>();
  const std::uint32_t bodies = in.get<std::uint32_t>();
  if (!snapshot || snapshot->frame != frame || !snapshot->bodyIds.empty() ||
      bodies != snapshot->bodies.size()) {
    throw RecordingError(context + " is malformed: body ids of frame " + std::to_string(frame) +
                         " for " + std::to_string(bodies) +
                         " bodies do not follow that frame's snapshot of as many bodies");
  }
  const std::vector<std::uint8_t> raw = decompressRest(
      in, std::size_t(bodies) * 4, context, "the body ids of frame " + std::to_string(frame),
      std::to_string(bodies) + " bodies'");
  Reader words(raw.data(), raw.size(), context);
  snapshot->bodyIds.resize(bodies);
  for (std::uint32_t& id : snapshot->bodyIds) id = words.get<std::uint32_t>();
}

WorldSnapshot readSnapshot(Reader& in, const std::string& context) {
  WorldSnapshot snapshot;
  snapshot.frame = in.get<std::uint64_t>();
  snapshot.steps = in.get<std::uint64_t>();
  snapshot.simulatedTime = in.get<double>();
  const std::uint32_t bodies = in.get<std::uint32_t>();
  const std::uint32_t particles = in.get<std::uint32_t>();
  const std::uint32_t forces = in.get<std::uint32_t>();
  // No World holds more (its particle limit, and a body has at least one particle): a larger
  // count is damage, refused before anything is allocated for it.
  if (bodies > kMaxParticleCapacity || particles > kMaxParticleCapacity ||
      forces > kMaxParticleCapacity) {
    throw RecordingError(context + " is malformed: the snapshot of frame " +
                         std::to_string(snapshot.frame) + " claims " + std::to_string(bodies) +
                         " bodies, " + std::to_string(particles) + " particles' contacts and " +
                         std::to_string(forces) + " particles' forces, more than a World holds (" +
                         std::to_string(kMaxParticleCapacity) + ")");
  }
  const std::size_t rawSize = std::size_t(bodies) * kSnapshotBodyBytes +
                              std::size_t(particles) * kSnapshotContactBytes +
                              std::size_t(forces) * kSnapshotForceBytes;
  const std::vector<std::uint8_t> raw = decompressRest(
      in, rawSize, context, "the snapshot of frame " + std::to_string(snapshot.frame),
      std::to_string(bodies) + " bodies, the contacts of " + std::to_string(particles) +
          " particles and the forces of " + std::to_string(forces) + " particles");
  Reader body(raw.data(), raw.size(), context);
  snapshot.bodies.resize(bodies);
  for (StoredBody& b : snapshot.bodies) {
    for (float& v : b.position) v = body.get<float>();
    std::array<float, 4> words{};
    for (float& v : words) v = body.get<float>();
    b.principalOrientation = {words[3], words[0], words[1], words[2]};  // orientationWords' order
    for (float& v : b.velocity) v = body.get<float>();
    for (float& v : b.angularVelocity) v = body.get<float>();
    const auto status = body.get<std::uint32_t>();
    b.alive = (status & 1u) != 0;
    b.calm = status >> 1;
  }
  snapshot.contacts.resize(particles);
  for (StoredContacts& c : snapshot.contacts) {
    for (auto& slot : c.slots) {
      for (std::uint32_t& word : slot) word = body.get<std::uint32_t>();
    }
    for (std::uint32_t& word : c.pairs) word = body.get<std::uint32_t>();
  }
  snapshot.forces.resize(forces);
  for (StoredForces& f : snapshot.forces) {
    for (std::uint32_t& word : f.force) word = body.get<std::uint32_t>();
    for (std::uint32_t& word : f.torque) word = body.get<std::uint32_t>();
  }
  return snapshot;
}

}  // namespace

struct RecordingWriter::Checksum {
  XXH3_state_t* state = XXH3_createState();
  Checksum() { XXH3_64bits_reset(state); }
  ~Checksum() { XXH3_freeState(state); }
  void update(const void* data, std::size_t size) { XXH3_64bits_update(state, data, size); }
  std::uint64_t digest() const { return XXH3_64bits_digest(state); }
};

const std::string* Recording::setting(std::string_view key) const {
  for (const auto& [name, value] : settings) {
    if (name == key) return &value;
  }
  return nullptr;
}

RecordingWriter::RecordingWriter(const std::filesystem::path& file,
                                 const std::vector<std::pair<std::string, std::string>>& settings)
    : m_file(file), m_checksum(std::make_unique<Checksum>()) {
  errno = 0;
  m_out.open(file, std::ios::binary | std::ios::trunc);
  if (!m_out) {
    throw Error("cannot write recording '" + file.string() +
                "': " + (errno ? std::strerror(errno) : "cannot open"));
  }
  Bytes header;
  header.putRaw(kMagic, sizeof kMagic);
  header.put(kRecordingVersion);
  m_checksum->update(header.data().data(), header.data().size());
  m_out.write(reinterpret_cast<const char*>(header.data().data()),
              std::streamsize(header.data().size()));
  m_bytes += header.data().size();
  Bytes payload;
  payload.put(std::uint32_t(settings.size()));
  for (const auto& [key, value] : settings) {
    payload.putText(key);
    payload.putText(value);
  }
  writeRecord(kSettingsTag, payload.data());
}

RecordingWriter::~RecordingWriter() = default;

void RecordingWriter::writeRecord(std::uint32_t recordTag,
                                  const std::vector<std::uint8_t>& payload) {
  Bytes header;
  header.put(recordTag);
  header.put(std::uint32_t(payload.size()));
  m_checksum->update(header.data().data(), header.data().size());
  m_checksum->update(payload.data(), payload.size());
  m_out.write(reinterpret_cast<const char*>(header.data().data()),
              std::streamsize(header.data().size()));
  m_out.write(reinterpret_cast<const char*>(payload.data()), std::streamsize(payload.size()));
  if (!m_out) throw Error("cannot write recording '" + m_file.string() + "': write failed");
  m_bytes += header.data().size() + payload.size();
}

void RecordingWriter::addFrame(const RecordedFrame& frame) {
  Bytes out;
  out.put(frame.frameDt);
  out.put(frame.steps);
  out.put(frame.simulatedTime);
  out.put(frame.stateHash);
  out.put(std::uint32_t(frame.inputs.size()));
  for (const RecordedInput& input : frame.inputs) {
    out.put(input.body);
    putBodyDesc(out, input.state);
  }
  out.put(std::uint32_t(frame.events.size()));
  out.putRaw(frame.events.data(), frame.events.size());
  writeRecord(kFrameTag, out.data());
  ++m_frames;
}

void RecordingWriter::addSnapshot(const WorldSnapshot& snapshot) {
  Bytes raw;
  for (const StoredBody& b : snapshot.bodies) {
    for (float v : b.position) raw.put(v);
    for (float v : orientationWords(b)) raw.put(v);
    for (float v : b.velocity) raw.put(v);
    for (float v : b.angularVelocity) raw.put(v);
    raw.put(statusWord(b));
  }
  for (const StoredContacts& c : snapshot.contacts) {
    for (const auto& slot : c.slots) {
      for (std::uint32_t word : slot) raw.put(word);
    }
    for (std::uint32_t word : c.pairs) raw.put(word);
  }
  for (const StoredForces& f : snapshot.forces) {
    for (std::uint32_t word : f.force) raw.put(word);
    for (std::uint32_t word : f.torque) raw.put(word);
  }
  // The reader (readSnapshot) takes the three counts for the layout of these bytes.
  SANDPHYS_ASSERT(raw.data().size() == snapshot.bodies.size() * kSnapshotBodyBytes +
                                           snapshot.contacts.size() * kSnapshotContactBytes +
                                           snapshot.forces.size() * kSnapshotForceBytes,
                  std::to_string(raw.data().size()) + " snapshot bytes for " +
                      std::to_string(snapshot.bodies.size()) + " bodies, " +
                      std::to_string(snapshot.contacts.size()) + " particles' contacts and " +
                      std::to_string(snapshot.forces.size()) + " particles' forces");
  Bytes out;
  out.put(snapshot.frame);
  out.put(snapshot.steps);
  out.put(snapshot.simulatedTime);
  out.put(std::uint32_t(snapshot.bodies.size()));
  out.put(std::uint32_t(snapshot.contacts.size()));
  out.put(std::uint32_t(snapshot.forces.size()));
  putCompressed(out, raw.data(), m_file);
  SANDPHYS_ASSERT(snapshot.rolling.empty() || snapshot.rolling.size() == snapshot.contacts.size(),
                  std::to_string(snapshot.rolling.size()) + " particles' rolling springs for " +
                      std::to_string(snapshot.contacts.size()) + " particles' contacts");
  writeRecord(kSnapshotTag, out.data());
  ++m_snapshots;
  if (!snapshot.rolling.empty()) addRolling(snapshot);
  if (snapshot.bodyIds.empty()) return;
  SANDPHYS_ASSERT(snapshot.bodyIds.size() == snapshot.bodies.size(),
                  std::to_string(snapshot.bodyIds.size()) + " body ids for " +
                      std::to_string(snapshot.bodies.size()) + " bodies");
  Bytes words;
  for (std::uint32_t id : snapshot.bodyIds) words.put(id);
  Bytes ids;
  ids.put(snapshot.frame);
  ids.put(std::uint32_t(snapshot.bodyIds.size()));
  putCompressed(ids, words.data(), m_file);
  writeRecord(kBodyIdsTag, ids.data());
}

void RecordingWriter::addRolling(const WorldSnapshot& snapshot) {
  Bytes springs;
  for (const StoredRolling& r : snapshot.rolling) {
    for (const auto& spring : r.springs) {
      for (std::uint32_t word : spring) springs.put(word);
    }
  }
  Bytes rolling;
  rolling.put(snapshot.frame);
  rolling.put(std::uint32_t(snapshot.rolling.size()));
  putCompressed(rolling, springs.data(), m_file);
  writeRecord(kRollingTag, rolling.data());
}

std::uint64_t RecordingWriter::finish(double wallSeconds) {
  if (m_finished) return m_bytes;
  Bytes out;
  out.put(m_frames);
  out.put(m_snapshots);
  out.put(wallSeconds);
  Bytes header;
  header.put(kEndTag);
  header.put(std::uint32_t(kEndPayloadBytes));
  // The checksum covers every byte of the file but its own eight.
  m_checksum->update(header.data().data(), header.data().size());
  m_checksum->update(out.data().data(), out.data().size());
  out.put(m_checksum->digest());
  m_out.write(reinterpret_cast<const char*>(header.data().data()),
              std::streamsize(header.data().size()));
  m_out.write(reinterpret_cast<const char*>(out.data().data()), std::streamsize(out.data().size()));
  m_out.close();
  if (!m_out) throw Error("cannot write recording '" + m_file.string() + "': write failed");
  m_bytes += header.data().size() + out.data().size();
  m_finished = true;
  return m_bytes;
}

Recording readRecording(const std::filesystem::path& file) {
  const std::string name = "recording '" + file.string() + "'";
  std::error_code ignored;
  if (std::filesystem::is_directory(file, ignored)) {
    throw RecordingError("cannot read " + name + ": it is a directory");
  }
  errno = 0;
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw RecordingError("cannot open " + name + ": " +
                         (errno ? std::strerror(errno) : "cannot open"));
  }
  const std::vector<std::uint8_t> data{std::istreambuf_iterator<char>(in),
                                       std::istreambuf_iterator<char>()};
  if (data.size() < kFileHeaderBytes || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    throw RecordingError(name + " is not a sandphys recording (it does not begin with " +
                         "SANDPHYSREC)");
  }
  std::uint32_t version = 0;
  std::memcpy(&version, data.data() + sizeof kMagic, sizeof version);
  if (version != kRecordingVersion) {
    throw RecordingError(name + " is in recording format version " + std::to_string(version) +
                         "; this build reads version " + std::to_string(kRecordingVersion) +
                         " only (docs/recording.md)");
  }

  // A whole file ends in its end record: check the checksum before reading anything else, so
  // that a damaged byte is reported as such rather than as whatever it broke.
  if (data.size() >= kFileHeaderBytes + kRecordHeaderBytes + kEndPayloadBytes) {
    const std::size_t endStart = data.size() - kEndPayloadBytes - kRecordHeaderBytes;
    std::uint32_t lastTag = 0;
    std::uint32_t lastLength = 0;
    std::memcpy(&lastTag, data.data() + endStart, 4);
    std::memcpy(&lastLength, data.data() + endStart + 4, 4);
    if (lastTag == kEndTag && lastLength == kEndPayloadBytes) {
      std::uint64_t stored = 0;
      std::memcpy(&stored, data.data() + data.size() - 8, 8);
      const std::uint64_t computed = XXH3_64bits(data.data(), data.size() - 8);
      if (stored != computed) {
        throw RecordingError(name + " is damaged: its checksum " + hex(stored) +
                             " does not match its contents (" + hex(computed) + ")");
      }
    }
  }

  Recording recording;
  recording.file = file;
  recording.bytes = data.size();
  bool settingsSeen = false;
  std::size_t offset = kFileHeaderBytes;
  while (true) {
    if (offset == data.size() || data.size() - offset < kRecordHeaderBytes) {
      throw RecordingError(name + " is truncated: it has no end record after " +
                           std::to_string(recording.frames.size()) +
                           " frames (was the recording interrupted?)");
    }
    std::uint32_t recordTag = 0;
    std::uint32_t length = 0;
    std::memcpy(&recordTag, data.data() + offset, 4);
    std::memcpy(&length, data.data() + offset + 4, 4);
    const std::size_t payloadStart = offset + kRecordHeaderBytes;
    if (length > data.size() - payloadStart) {
      throw RecordingError(name + " is truncated: it ends inside a '" + tagText(recordTag) +
                           "' record after " + std::to_string(recording.frames.size()) +
                           " frames (was the recording interrupted?)");
    }
    Reader payload(data.data() + payloadStart, length, name);
    if (recordTag == kEndTag) {
      if (length != kEndPayloadBytes) {
        throw RecordingError(name + " is malformed: its end record has " + std::to_string(length) +
                             " bytes instead of " + std::to_string(kEndPayloadBytes));
      }
      const auto frames = payload.get<std::uint64_t>();
      const auto snapshots = payload.get<std::uint64_t>();
      recording.wallSeconds = payload.get<double>();
      const auto stored = payload.get<std::uint64_t>();
      const std::uint64_t computed = XXH3_64bits(data.data(), payloadStart + length - 8);
      if (stored != computed) {
        throw RecordingError(name + " is damaged: its checksum " + hex(stored) +
                             " does not match its contents (" + hex(computed) + ")");
      }
      if (payloadStart + length != data.size()) {
        throw RecordingError(
            name + " is malformed: " + std::to_string(data.size() - payloadStart - length) +
            " bytes follow its end record");
      }
      if (frames != recording.frames.size() || snapshots != recording.snapshots.size()) {
        throw RecordingError(name + " is malformed: its end record counts " +
                             std::to_string(frames) + " frames and " + std::to_string(snapshots) +
                             " snapshots, the file holds " +
                             std::to_string(recording.frames.size()) + " and " +
                             std::to_string(recording.snapshots.size()));
      }
      return recording;
    }
    if (!settingsSeen && recordTag != kSettingsTag) {
      throw RecordingError(name + " is malformed: it does not begin with its settings");
    }
    if (recordTag == kSettingsTag) {
      const std::uint32_t count = payload.get<std::uint32_t>();
      for (std::uint32_t i = 0; i < count; ++i) {
        std::string key = payload.getText();
        std::string value = payload.getText();
        if (recording.setting(key)) {
          throw RecordingError(name + " is malformed: its settings give '" + key + "' twice");
        }
        recording.settings.emplace_back(std::move(key), std::move(value));
      }
      settingsSeen = true;
    } else if (recordTag == kFrameTag) {
      recording.frames.push_back(readFrame(payload, name, recording.frames.size()));
    } else if (recordTag == kSnapshotTag) {
      recording.snapshots.push_back(readSnapshot(payload, name));
    } else if (recordTag == kRollingTag) {
      readRolling(payload, name,
                  recording.snapshots.empty() ? nullptr : &recording.snapshots.back());
    } else if (recordTag == kBodyIdsTag) {
      readBodyIds(payload, name,
                  recording.snapshots.empty() ? nullptr : &recording.snapshots.back());
    } else {
      throw RecordingError(name + " is malformed: unknown record '" + tagText(recordTag) +
                           "' at byte " + std::to_string(offset));
    }
    offset = payloadStart + length;
  }
}

}  // namespace sandphys
