#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "bench_run.h"
#include "support/test_folder.h"

namespace sandphys::testing {
namespace {

// The small box pile with rolling friction, settled until it sleeps whole, then timed for 1000
// substeps in calls of 100.
const std::string kSleepingBench =
    smallBoxBench(4000, 1000) +
    " --sleep --rolling-friction 0.1 --chunk 100 --no-kernel-times --pile-cache ";

// --frames times World::step frames of --chunk substeps: on sand that all sleeps the first frame
// runs its first substep and skips the rest as idle, and the frames after it skip every substep;
// World::substep runs them all. The pile ends the same either way.
TEST(BenchFrames, FramesOfSleepingSandRunOneSubstepInAll) {
  TestFolder folder("sandphys_bench_frames_");
  const std::string bench = kSleepingBench + (folder.path() / "piles").string();
  const nlohmann::json framed = benchSize(bench + " --frames", folder.path() / "framed.json");
  const nlohmann::json substeps = benchSize(bench, folder.path() / "substeps.json");
  ASSERT_EQ(framed.at("granules_asleep_at_start"), framed.at("granules"))
      << "the pile did not sleep whole: nothing to skip";
  EXPECT_EQ(framed.at("steps"), 1000);
  EXPECT_EQ(framed.at("idle_substeps"), 1000 - 1);
  EXPECT_EQ(framed.at("idle_frames"), 10);
  EXPECT_EQ(substeps.at("steps"), 1000);
  EXPECT_EQ(substeps.at("idle_substeps"), 0);
  EXPECT_EQ(framed.at("state").at("measured"), substeps.at("state").at("measured"));
}

TEST(BenchFrames, IsRefusedWithTheOptionsThatRunTheirOwnLoops) {
  const ProcessResult result =
      runCommand(smallBoxBench(10, 10) + " --frames --compare-shaders built-in");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_NE(result.output.find("--frames with --sandbox or --compare-shaders"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace sandphys::testing
