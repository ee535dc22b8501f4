#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "bench_run.h"
#include "support/test_folder.h"

namespace sandphys::testing {
namespace {

namespace fs = std::filesystem;

// A small box pile, briefly settled, timed for 100 substeps and then run in LAMMPS.
const std::string kBench = smallBoxBench(2000, 100) + " --no-kernel-times --lammps-ranks 1";

class LammpsSideBySide : public ::testing::Test {
 protected:
  // One run, with `options` more; its JSON's only size, and its output.
  nlohmann::json run(const std::string& prefix, std::string& output,
                     const std::string& options = "") {
    return benchSize(prefix + kBench + options + " --lammps-dir " + (m_dir / "decks").string(),
                     m_dir / "bench.json", &output);
  }

  TestFolder m_folder{"sandphys_bench_lammps_"};
  const fs::path& m_dir = m_folder.path();
};

TEST_F(LammpsSideBySide, RunsTheTimedPileForAsManyStepsAndReportsItsLoopTime) {
  std::string output;
  const nlohmann::json size = run("", output);
  ASSERT_EQ(size.at("lammps").size(), 1u) << output;
  const nlohmann::json& lammps = size["lammps"][0];
  EXPECT_EQ(lammps["failure"], "") << output;
  EXPECT_EQ(lammps["ranks"], 1);
  EXPECT_EQ(lammps["steps"], size["steps"]);
  EXPECT_GT(lammps["loop_seconds"].get<double>(), 0.0);
  EXPECT_NE(output.find("Side by side with LAMMPS"), std::string::npos) << output;
  // The deck holds the pile sandphys timed: every particle of it, in the folder named by size.
  const fs::path deck = m_dir / "decks" / "box-256";
  EXPECT_EQ(lammps["deck"], deck.string());
  const LammpsRun log = readLammpsRun(deck);
  ASSERT_FALSE(log.thermo.empty());
  EXPECT_EQ(log.thermo.front().atoms, size["particles"].get<double>());
  EXPECT_EQ(log.loopRanks, 1);
}

TEST_F(LammpsSideBySide, ALammpsThatCannotRunIsNamedAndTheBenchStillReports) {
  std::string output;
  // No lmp on the PATH.
  const nlohmann::json size = run("env PATH=" + (m_dir / "nothing").string() + " ", output);
  ASSERT_EQ(size.at("lammps").size(), 1u) << output;
  const std::string failure = size["lammps"][0]["failure"];
  EXPECT_NE(failure.find("lmp -in in.sandphys"), std::string::npos) << failure;
  EXPECT_NE(failure.find("lammps.out"), std::string::npos) << failure;
  EXPECT_TRUE(size["lammps"][0]["ms_per_step"].is_null());
  EXPECT_NE(output.find("did not run"), std::string::npos) << output;
  EXPECT_GT(size["granule_steps_per_second"].get<double>(), 0.0);
}

TEST_F(LammpsSideBySide, InRoundsEachRoundOfSandphysIsFollowedByOneOfLammps) {
  std::string output;
  const nlohmann::json size = run("", output, " --lammps-rounds 2");
  ASSERT_EQ(size.at("lammps").size(), 1u) << output;
  const nlohmann::json& lammps = size["lammps"][0];
  EXPECT_EQ(lammps["failure"], "") << output;
  // Two rounds of 50 substeps, each paired with a LAMMPS run of 50 steps.
  const nlohmann::json& walls = size.at("round_wall_seconds");
  const nlohmann::json& loops = lammps.at("round_loop_seconds");
  ASSERT_EQ(walls.size(), 2u) << output;
  ASSERT_EQ(loops.size(), 2u) << output;
  EXPECT_EQ(size["steps"], 100);
  EXPECT_EQ(lammps["steps"], 100);
  EXPECT_EQ(readLammpsRun(m_dir / "decks" / "box-256").loopSteps, 50u);
  EXPECT_NEAR(walls[0].get<double>() + walls[1].get<double>(), size["wall_seconds"].get<double>(),
              1e-9);
  EXPECT_NEAR(loops[0].get<double>() + loops[1].get<double>(), lammps["loop_seconds"].get<double>(),
              1e-9);
  // The median of two rounds' ratios is their mean.
  const double mean = 0.5 * (loops[0].get<double>() / walls[0].get<double>() +
                             loops[1].get<double>() / walls[1].get<double>());
  EXPECT_NEAR(lammps["sandphys_speed_ratio_median_of_rounds"].get<double>(), mean, 1e-9 * mean);
  EXPECT_NE(output.find("in 2 round(s)"), std::string::npos) << output;
}

TEST_F(LammpsSideBySide, RoundsOfUnequalLengthAreAUsageError) {
  const ProcessResult result = runCommand(kBench + " --lammps-rounds 3");
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_NE(result.output.find("--steps 100 with --lammps-rounds 3"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace sandphys::testing
