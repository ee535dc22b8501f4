// Every registered scene, small, recorded through the samples app's recorder and replayed from the
// file: every frame's hash, input and snapshot agree bit for bit. A replay perturbed by one unit
// in the last place of one granule's velocity is caught at that frame and names the granule; a
// recording of a scene this build does not have, or with settings it refuses, is named.
#include <gtest/gtest.h>

#include <bit>
#include <filesystem>
#include <fstream>

#include "app/golden.h"
#include "app/recording.h"
#include "app/replay.h"
#include "app/run.h"
#include "replay/recorded_scene.h"
#include "scenes/registry.h"
#include "support/every_scene.h"
#include "support/test_world.h"

namespace sandphys::samples {
namespace {

class SceneReplay : public ::testing::TestWithParam<const scenes::SceneEntry*> {};

TEST_P(SceneReplay, ReplaysBitIdenticallyAndKeepsToItsGolden) {
  const std::string name(GetParam()->name);
  const std::filesystem::path file = tempRecording(name);
  std::unique_ptr<scenes::Scene> scene = goldenScene(name);
  const RunSummary run = recordScene(*scene, file, kGoldenFrames, 5);
  ASSERT_EQ(run.frames, kGoldenFrames);

  const Recording recording = readRecording(file);
  ASSERT_EQ(recording.frames.size(), kGoldenFrames);
  // Snapshots after build, at frames 5 and 10, and at the end.
  ASSERT_EQ(recording.snapshots.size(), 4u);
  EXPECT_EQ(recording.snapshots.back().frame, kGoldenFrames);
  EXPECT_EQ(*recording.setting("scene"), name);
  // The state moved: a hash that did not change would check nothing.
  EXPECT_NE(recording.frames.front().stateHash, recording.frames.back().stateHash);
  EXPECT_EQ(recording.frames.back().steps, run.stats.steps);

  const ReplayResult replay = replayRecording(testing::gpu(), recording);
  EXPECT_TRUE(replay.identical) << replay.difference;
  EXPECT_EQ(replay.frames, kGoldenFrames);
  std::filesystem::remove(file);

  const std::filesystem::path goldenFile =
      std::filesystem::path(SANDPHYS_GOLDEN_DIR) / (name + ".json");
  std::ifstream in(goldenFile);
  ASSERT_TRUE(in) << "no golden " << goldenFile
                  << "; make the goldens on purpose with: sandphys-samples --write-goldens "
                     "tests/golden (docs/recording.md)";
  const nlohmann::json golden = nlohmann::json::parse(in);
  const std::vector<std::string> outside = compareWithGolden(goldenMetrics(run, *scene), golden);
  std::string text;
  for (const std::string& line : outside) text += "\n  " + line;
  EXPECT_TRUE(outside.empty()) << name << " left its golden " << goldenFile << ":" << text;
}

INSTANTIATE_TEST_SUITE_P(EveryScene, SceneReplay, ::testing::ValuesIn(testing::registeredScenes()),
                         testing::sceneTestName);

// The same with sleeping sand (--sleep): the sleep code path records and replays bit for bit.
// The paper's law has no static friction and refuses sleep, by name.
class SleepingSceneReplay : public ::testing::TestWithParam<const scenes::SceneEntry*> {};

TEST_P(SleepingSceneReplay, ReplaysBitIdentically) {
  const std::string name(GetParam()->name);
  std::unique_ptr<scenes::Scene> scene = goldenScene(name);
  scene->setSleep(true);
  if (scene->contactLaw() == ContactLaw::PaperViscous) {
    try {
      World world(testing::gpu(), scene->settings());
      ADD_FAILURE() << name << ": the paper's law with sleep was accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("WorldSettings.contactLaw"), std::string::npos);
    }
    return;
  }
  const std::filesystem::path file = tempRecording(name + "-sleep");
  const RunSummary run = recordScene(*scene, file, kGoldenFrames, 5);
  ASSERT_EQ(run.frames, kGoldenFrames);
  const Recording recording = readRecording(file);
  const std::string* sleepSetting = recording.setting(std::string(kWorldPrefix) + "sleep");
  ASSERT_NE(sleepSetting, nullptr);
  EXPECT_EQ(*sleepSetting, "1");
  EXPECT_NE(recording.frames.front().stateHash, recording.frames.back().stateHash);
  const ReplayResult replay = replayRecording(testing::gpu(), recording);
  EXPECT_TRUE(replay.identical) << replay.difference;
  EXPECT_EQ(replay.frames, kGoldenFrames);
  std::filesystem::remove(file);
}

INSTANTIATE_TEST_SUITE_P(EveryScene, SleepingSceneReplay,
                         ::testing::ValuesIn(testing::registeredScenes()), testing::sceneTestName);

// With rolling friction the recording's snapshots carry the rolling springs (ROLL records) and a
// replay is bit-identical, snapshots included.
TEST(RollingFrictionReplay, ReplaysBitIdenticallyWithTheRollingSpringsInItsSnapshots) {
  const std::string name = "sand-box-pour";
  std::unique_ptr<scenes::Scene> scene = goldenScene(name);
  scene->setRollingFriction(0.1f);
  const std::filesystem::path file = tempRecording(name + "-rolling");
  const RunSummary run = recordScene(*scene, file, kGoldenFrames, 5);
  ASSERT_EQ(run.frames, kGoldenFrames);
  const Recording recording = readRecording(file);
  ASSERT_FALSE(recording.snapshots.empty());
  const WorldSnapshot& last = recording.snapshots.back();
  EXPECT_EQ(last.rolling.size(), last.contacts.size());
  std::size_t loaded = 0;
  for (const StoredRolling& r : last.rolling) {
    for (const auto& spring : r.springs) loaded += spring != decltype(spring){};
  }
  EXPECT_GT(loaded, 0u) << "no rolling spring in use at frame " << last.frame;
  const ReplayResult replay = replayRecording(testing::gpu(), recording);
  EXPECT_TRUE(replay.identical) << replay.difference;
  EXPECT_EQ(replay.frames, kGoldenFrames);
  std::filesystem::remove(file);
}

TEST(PerturbedReplay, IsCaughtAtTheFrameAndNamesTheGranule) {
  constexpr std::uint32_t kGranule = 21;
  constexpr std::uint64_t kFrame = 10;
  const std::filesystem::path file = tempRecording("perturbed");
  std::unique_ptr<scenes::Scene> scene = goldenScene("box-drop");
  recordScene(*scene, file, 12, 1);
  Recording recording = readRecording(file);
  std::filesystem::remove(file);
  const ReplayHook nudge = [&](World& world, std::uint64_t frame) {
    if (frame == kFrame) testing::flipVelocityBit(world, kGranule, 1);
  };
  // With the frame's own snapshot: the granule, the field and both values one bit apart.
  ReplayResult replay = replayRecording(testing::gpu(), recording, nudge);
  EXPECT_FALSE(replay.identical);
  EXPECT_EQ(replay.firstDifferentFrame, kFrame) << replay.difference;
  EXPECT_NE(replay.difference.find("state hash"), std::string::npos) << replay.difference;
  EXPECT_NE(replay.difference.find("body 21 velocity.y"), std::string::npos) << replay.difference;

  // With the end's snapshot only (as with --snapshot-every 60): the frame from the hash, the values
  // from the next snapshot, if the difference lasts until then.
  recording.snapshots.erase(recording.snapshots.begin() + 1, recording.snapshots.end() - 1);
  ASSERT_EQ(recording.snapshots.back().frame, 12u);
  replay = replayRecording(testing::gpu(), recording, nudge);
  EXPECT_FALSE(replay.identical);
  EXPECT_EQ(replay.firstDifferentFrame, kFrame) << replay.difference;
  EXPECT_NE(replay.difference.find("next snapshot (frame 12)"), std::string::npos)
      << replay.difference;
}

// A recording with these settings and no frames.
std::filesystem::path recordingWith(const std::string& name,
                                    const std::vector<std::pair<std::string, std::string>>& s) {
  const std::filesystem::path file = tempRecording(name);
  RecordingWriter writer(file, s);
  writer.finish(0.0);
  return file;
}

std::string replayError(const std::filesystem::path& file) {
  try {
    (void)replayRecording(testing::gpu(), readRecording(file));
  } catch (const RecordingError& error) {
    return error.what();
  }
  return {};
}

TEST(BadRecording, OfASceneThisBuildDoesNotHaveIsNamed) {
  const auto file = recordingWith("gone", {{"scene", "sand-castle"}});
  const std::string message = replayError(file);
  EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
  EXPECT_NE(message.find("scene 'sand-castle', which this build does not have"), std::string::npos)
      << message;
}

TEST(BadRecording, WithSettingsThisBuildRefusesIsNamed) {
  // A parameter out of today's range, one the scene no longer has, and a combination that the
  // scene's settings refuse (more granules than a World holds).
  const auto outOfRange =
      recordingWith("range", {{"scene", "box-drop"}, {"param:diameter", "-0.02"}});
  std::string message = replayError(outOfRange);
  EXPECT_NE(message.find("refuses its setting param:diameter = -0.02"), std::string::npos)
      << message;
  EXPECT_NE(message.find(outOfRange.filename().string()), std::string::npos) << message;

  const auto unknown = recordingWith("unknown", {{"scene", "box-drop"}, {"param:colour", "red"}});
  message = replayError(unknown);
  EXPECT_NE(message.find("refuses its setting param:colour = red"), std::string::npos) << message;

  const auto tooMany =
      recordingWith("too-many", {{"scene", "box-drop"}, {"param:block", "1000,1000,1000"}});
  message = replayError(tooMany);
  EXPECT_NE(message.find("refuses"), std::string::npos) << message;
  EXPECT_NE(message.find(tooMany.filename().string()), std::string::npos) << message;

  // World settings: one this build does not know, one it cannot read, one beyond its limits.
  const auto world =
      recordingWith("world", {{"scene", "box-drop"}, {"world:sand_colour", "yellow"}});
  message = replayError(world);
  EXPECT_NE(message.find("refuses its setting world:sand_colour = yellow"), std::string::npos)
      << message;
  const auto unreadable =
      recordingWith("unreadable", {{"scene", "box-drop"}, {"world:max_bodies", "many"}});
  message = replayError(unreadable);
  EXPECT_NE(message.find("refuses its setting world:max_bodies = many"), std::string::npos)
      << message;
  const auto beyond =
      recordingWith("beyond", {{"scene", "box-drop"}, {"world:max_particles", "4000000000"}});
  message = replayError(beyond);
  EXPECT_NE(message.find("refuses the World it records"), std::string::npos) << message;
  EXPECT_NE(message.find("maxParticles = 4000000000"), std::string::npos) << message;
}

}  // namespace
}  // namespace sandphys::samples
