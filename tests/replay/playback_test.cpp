// The viewer's --play timeline without the window: frames re-simulated in order and checked, the
// recorded snapshots shown at once, the re-simulated state put back bit for bit, and going on from
// a snapshot re-simulating, so that a scene with state of its own (the avalanche's Bullet world)
// still matches every recorded hash.
#include <gtest/gtest.h>

#include "app/golden.h"
#include "app/playback.h"
#include "replay/recorded_scene.h"
#include "support/test_world.h"

namespace sandphys::samples {
namespace {

constexpr std::uint64_t kFrames = 12;
constexpr double kAllOfIt = 1e9;  // ms: advance() runs to its target

Recording recorded(const std::string& sceneName, std::uint64_t snapshotEvery) {
  const std::filesystem::path file = tempRecording("playback_" + sceneName);
  std::unique_ptr<scenes::Scene> scene = goldenScene(sceneName);
  recordScene(*scene, file, kFrames, snapshotEvery);
  Recording recording = readRecording(file);
  std::filesystem::remove(file);
  return recording;
}

// The World's state hash against the one recorded for `frame`.
void expectShows(Playback& playback, std::uint64_t frame) {
  ASSERT_EQ(playback.shownFrame(), frame);
  ASSERT_GE(frame, 1u);
  EXPECT_EQ(playback.world().readStateHash(), playback.recording().frames[frame - 1].stateHash)
      << "frame " << frame;
}

TEST(Playback, ScrubsToSnapshotsAndGoesOnExactlyInASceneCoupledToBullet) {
  Playback playback(testing::gpu(), recorded("avalanche", 3));
  ASSERT_EQ(playback.frames(), kFrames);
  EXPECT_EQ(playback.shownFrame(), 0u);

  // Forward with no snapshot on the way: re-simulated, one frame per advance with no time budget.
  playback.scrubTo(2);
  EXPECT_TRUE(playback.busy());
  ASSERT_TRUE(playback.advance(0.0));
  expectShows(playback, 1);
  // Forward past a snapshot: the scene adds no bodies, so the snapshot shows at once, and going
  // on from it re-simulates from the furthest frame (1) up to the next.
  playback.scrubTo(7);
  EXPECT_FALSE(playback.busy());
  EXPECT_TRUE(playback.showingSnapshot());
  expectShows(playback, 6);
  playback.playOn(1);
  EXPECT_FALSE(playback.showingSnapshot());
  EXPECT_EQ(playback.shownFrame(), 1u);
  playback.advance(kAllOfIt);
  EXPECT_FALSE(playback.busy());
  expectShows(playback, 7);

  // Back: the snapshot at or before the frame, at once.
  playback.scrubTo(5);
  EXPECT_FALSE(playback.busy());
  EXPECT_TRUE(playback.showingSnapshot());
  expectShows(playback, 3);
  EXPECT_EQ(playback.snapshotBefore(), 0u);
  EXPECT_EQ(playback.snapshotAfter(), 6u);
  EXPECT_FALSE(playback.advance(kAllOfIt)) << "a shown snapshot re-simulates nothing";

  // To the furthest frame re-simulated: its own state again, the frame time it had not stepped
  // included, and it goes on from there as recorded (every frame's hash is checked).
  playback.scrubTo(7);
  EXPECT_FALSE(playback.showingSnapshot());
  expectShows(playback, 7);
  playback.playOn(kFrames);
  playback.advance(kAllOfIt);
  expectShows(playback, kFrames);

  // Going on from a snapshot: the scene is built again and re-simulated up to it.
  playback.scrubTo(8);
  expectShows(playback, 6);
  playback.playOn(2);
  EXPECT_TRUE(playback.busy());
  playback.advance(kAllOfIt);
  EXPECT_FALSE(playback.showingSnapshot());
  EXPECT_EQ(playback.simulatedFrame(), 8u);
  expectShows(playback, 8);
  playback.playOn(kFrames);
  playback.advance(kAllOfIt);
  expectShows(playback, kFrames);

  EXPECT_FALSE(playback.mismatch()) << playback.mismatch()->what;
  EXPECT_EQ(playback.checkedFrames(), kFrames);
}

// A snapshot holding more bodies than the World has so far (bodies added on the way, as a batch
// or an emitter adds them) is not shown ahead: the timeline re-simulates to it instead, and there
// the snapshot is compared in full.
TEST(Playback, ReSimulatesToASnapshotWhoseBodiesTheWorldHasNotYet) {
  Recording recording = recorded("box-drop", 3);
  ASSERT_EQ(recording.snapshots[1].frame, 3u);
  recording.snapshots[1].bodies.push_back(recording.snapshots[1].bodies.back());
  Playback playback(testing::gpu(), std::move(recording));
  playback.scrubTo(5);
  EXPECT_FALSE(playback.showingSnapshot());
  EXPECT_TRUE(playback.busy());
  playback.advance(kAllOfIt);
  expectShows(playback, 5);
  ASSERT_TRUE(playback.mismatch());
  EXPECT_EQ(playback.mismatch()->frame, 3u);
  EXPECT_NE(playback.mismatch()->what.find("body count"), std::string::npos)
      << playback.mismatch()->what;
}

TEST(Playback, NamesTheFirstFrameThatDiffersFromTheRecording) {
  Recording recording = recorded("box-drop", 6);
  recording.frames[7].stateHash ^= 1u;  // frame 8
  recording.frames[9].stateHash ^= 1u;  // frame 10
  Playback playback(testing::gpu(), std::move(recording));
  playback.playOn(kFrames);
  playback.advance(kAllOfIt);
  ASSERT_TRUE(playback.mismatch());
  EXPECT_EQ(playback.mismatch()->frame, 8u);
  EXPECT_NE(playback.mismatch()->what.find("frame 8: state hash recorded"), std::string::npos)
      << playback.mismatch()->what;
  EXPECT_NE(playback.mismatch()->what.find("no snapshot"), std::string::npos)
      << playback.mismatch()->what;
}

}  // namespace
}  // namespace sandphys::samples
