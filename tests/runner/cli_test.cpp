// The sandphys-samples command line: usage errors exit non-zero and name the flag and the value.
// None of these reach the GPU.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "process.h"

namespace sandphys::testing {
namespace {

std::string samplesCommand(const std::string& arguments) {
  return std::string("'") + SANDPHYS_SAMPLES_EXE + "' " + arguments;
}

ProcessResult runSamples(const std::string& arguments) {
  return runCommand(samplesCommand(arguments));
}

void expectUsageError(const std::string& arguments, std::initializer_list<const char*> named) {
  expectUsageErrorOf(samplesCommand(arguments), arguments, named);
}

TEST(SamplesCli, UnknownFlag) {
  expectUsageError("--headless --bogus-flag", {"--bogus-flag"});
}

TEST(SamplesCli, NegativeFrames) {
  expectUsageError("--frames -5", {"--frames", "-5"});
}

TEST(SamplesCli, FramesNotANumber) {
  expectUsageError("--frames lots", {"--frames", "lots"});
}

TEST(SamplesCli, FrameDtNotPositive) {
  expectUsageError("--frame-dt 0", {"--frame-dt"});
}

TEST(SamplesCli, UnknownScene) {
  expectUsageError("--headless --scene no-such-scene", {"--scene", "no-such-scene"});
}

TEST(SamplesCli, BatchNeedsThreePositiveCounts) {
  expectUsageError("--batch 8 0 8", {"--batch", "8,0,8"});
  expectUsageError("--batch 8 8", {"--batch"});
  expectUsageError("--batches -2", {"--batches", "-2"});
}

TEST(SamplesCli, ParameterOfAnotherScene) {
  expectUsageError("--scene box-drop --batches 3", {"--batches", "batches"});
  expectUsageError("--param nonsense", {"--param", "nonsense"});
}

TEST(SamplesCli, ExportNeedsAKnownExtension) {
  expectUsageError("--export granules.txt", {"--export", "granules.txt", ".txt"});
}

TEST(SamplesCli, UnwritablePathsAreRefusedBeforeRunning) {
  const std::string missing = "/nonexistent-sandphys-dir/metrics.json";
  expectUsageError("--metrics " + missing, {"--metrics", missing.c_str()});
  expectUsageError("--export /nonexistent-sandphys-dir/g.csv",
                   {"--export", "/nonexistent-sandphys-dir/g.csv"});
  const std::string directory = std::filesystem::temp_directory_path().string();
  expectUsageError("--metrics " + directory, {"--metrics", directory.c_str()});
}

TEST(SamplesCli, ListPrintsTheRegistry) {
  const ProcessResult result = runSamples("--list");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("cylinder-pile"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("box-drop"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("batches = 1"), std::string::npos) << result.output;
}

TEST(SamplesCli, HelpNamesTheFlags) {
  const ProcessResult result = runSamples("--help");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  for (const char* flag : {"--scene", "--headless", "--frames", "--frame-dt", "--metrics",
                           "--export", "--batches", "--batch", "--seed", "--list"}) {
    EXPECT_NE(result.output.find(flag), std::string::npos) << flag;
  }
}

}  // namespace
}  // namespace sandphys::testing
