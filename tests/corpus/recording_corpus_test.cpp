// Recordings damaged in every way a generator can think of: cut at every length, one byte flipped
// at every offset, and values edited at every offset with the checksum then fixed, so that only
// the reader's own checks stand between the edit and the World. Each either reads or fails with
// a RecordingError that names the file; nothing else is thrown (std::bad_alloc included), and the
// process runs under an address-space bound so that a runaway allocation fails instead of paging.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <sys/resource.h>
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "corpus/corpus_exit.h"

namespace sandphys::corpus {
namespace {

using Bytes = std::vector<char>;

std::filesystem::path corpusFile(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("sandphys-corpus-" + std::to_string(::getpid()) + "-" + name);
}

// A small but complete recording: settings, frames with inputs and events, snapshots of bodies
// with contact history.
Bytes sampleRecording() {
  const std::filesystem::path file = corpusFile("sample.sprec");
  {
    RecordingWriter writer(file, {{"scene", "box-drop"}, {"param:seed", "7"}, {"world:dt", "1"}});
    for (std::uint64_t frame = 0; frame <= 6; ++frame) {
      if (frame % 3 == 0) {
        WorldSnapshot s;
        s.frame = frame;
        s.steps = 10 * frame;
        s.simulatedTime = 1e-3 * double(frame);
        for (std::uint32_t i = 0; i < 3; ++i) {
          StoredBody b;
          b.position = {float(i), 0.5f, -float(frame)};
          b.principalOrientation = {.w = 0.8f, .x = 0.0f, .y = 0.6f, .z = 0.0f};
          b.velocity = {0.1f, -0.2f, 0.3f};
          b.calm = i;
          s.bodies.push_back(b);
        }
        s.contacts.resize(12);
        s.contacts[5].pairs = {1, 0, 0, 1};
        s.contacts[5].slots[0] = {0x3c23d70a, 0, 0xbc23d70a, 17};
        writer.addSnapshot(s);
      }
      if (frame > 0) {
        RecordedFrame f;
        f.frameDt = 1.0f / 60.0f;
        f.steps = 10 * frame;
        f.simulatedTime = 1e-3 * double(frame);
        f.stateHash = 0x9e3779b97f4a7c15ull * frame;
        f.inputs.push_back({1, BodyDesc{.position = {0, 1, 0}, .motion = Motion::Kinematic}});
        f.events = {1, 2, 3};
        writer.addFrame(f);
      }
    }
    writer.finish(1.5);
  }
  std::ifstream in(file, std::ios::binary);
  Bytes bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::filesystem::remove(file);
  return bytes;
}

void fixChecksum(Bytes& bytes) {
  const std::uint64_t sum = XXH3_64bits(bytes.data(), bytes.size() - 8);
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
}

// Writes `bytes` and reads them back: true when read, false for a RecordingError naming the
// file; anything else fails the test, naming the damage.
bool readsOrNamesTheFile(const Bytes& bytes, const std::string& damage) {
  static const std::filesystem::path file = corpusFile("damaged.sprec");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
  }
  try {
    (void)readRecording(file);
    return true;
  } catch (const RecordingError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos)
        << damage << ": " << error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << damage << ": not a RecordingError: " << error.what();
  }
  return false;
}

class RecordingCorpus : public ::testing::Test {
 protected:
  void SetUp() override {
#if !defined(__SANITIZE_ADDRESS__)
    const rlimit memory{kProbeBytes, kProbeBytes};  // AddressSanitizer reserves far more
    setrlimit(RLIMIT_AS, &memory);
#endif
    m_sample = sampleRecording();
    ASSERT_TRUE(readsOrNamesTheFile(m_sample, "the undamaged sample"));
  }
  Bytes m_sample;
};

TEST_F(RecordingCorpus, CutAtEveryLengthIsRefused) {
  for (std::size_t length = 0; length < m_sample.size(); ++length) {
    EXPECT_FALSE(readsOrNamesTheFile(Bytes(m_sample.begin(), m_sample.begin() + long(length)),
                                     "cut at " + std::to_string(length)));
  }
}

TEST_F(RecordingCorpus, AFlippedByteAtEveryOffsetIsRefused) {
  for (std::size_t at = 0; at < m_sample.size(); ++at) {
    for (const unsigned char bit : {0x01, 0x80}) {
      Bytes bytes = m_sample;
      bytes[at] = char(bytes[at] ^ bit);
      EXPECT_FALSE(
          readsOrNamesTheFile(bytes, "byte " + std::to_string(at) + " ^ " + std::to_string(bit)));
    }
  }
}

TEST_F(RecordingCorpus, ValuesEditedWithTheChecksumFixedReadOrAreNamed) {
  std::size_t read = 0;
  std::size_t refused = 0;
  const auto tryEdit = [&](const std::function<void(Bytes&)>& edit, const std::string& damage) {
    Bytes bytes = m_sample;
    edit(bytes);
    fixChecksum(bytes);
    (readsOrNamesTheFile(bytes, damage) ? read : refused) += 1;
  };
  for (std::size_t at = 0; at + 8 < m_sample.size(); ++at) {
    for (const unsigned char value : {0x00, 0xff, 0x7f}) {
      tryEdit([&](Bytes& b) { b[at] = char(value); },
              "byte " + std::to_string(at) + " = " + std::to_string(value));
    }
    for (const std::uint32_t word : {0xffffffffu, 0x7fc00000u, 0x80000000u, 0x00100000u}) {
      if (at + 4 > m_sample.size() - 8) continue;
      tryEdit([&](Bytes& b) { std::memcpy(b.data() + at, &word, 4); },
              "word at " + std::to_string(at) + " = " + std::to_string(word));
    }
  }
  std::printf("%zu edits with the checksum fixed: %zu read, %zu refused naming the file\n",
              read + refused, read, refused);
  EXPECT_GT(refused, 0u);
}

}  // namespace
}  // namespace sandphys::corpus
