// The screenshot flags of sandphys-samples: bad values are usage errors (exit 2) that name the
// flag and the value, found before any simulation; a tiny headless run writes a PNG of the size
// asked for.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <filesystem>
#include <string>

#include "runner/process.h"

namespace sandphys::testing {
namespace {

std::string samplesCommand(const std::string& arguments) {
  return std::string("'") + SANDPHYS_SAMPLES_EXE + "' --headless " + arguments;
}

ProcessResult runSamples(const std::string& arguments) {
  return runCommand(samplesCommand(arguments));
}

void expectUsageError(const std::string& arguments, std::initializer_list<const char*> named) {
  expectUsageErrorOf(samplesCommand(arguments), arguments, named);
}

TEST(ScreenshotCli, BadSizeIsAUsageError) {
  expectUsageError("--size 0x10", {"--size", "0x10"});
  expectUsageError("--size abc", {"--size", "abc"});
  expectUsageError("--size 640x", {"--size", "640x"});
  expectUsageError("--size 20000x100", {"--size", "20000x100"});
}

TEST(ScreenshotCli, EveryMustBePositiveAndNeedsAFolder) {
  const std::string dir = std::string(SANDPHYS_RENDER_TEST_OUTPUT) + "/every_zero";
  expectUsageError("--screenshots " + dir + " --every 0", {"--every", "0"});
  expectUsageError("--screenshots " + dir + " --every -3", {"--every", "-3"});
  expectUsageError("--every 5", {"--every", "--screenshots"});
}

TEST(ScreenshotCli, UnwritableScreenshotPathIsRefusedBeforeRunning) {
  const std::string missing = "/nonexistent-sandphys-dir/shot.png";
  expectUsageError("--screenshot " + missing, {"--screenshot", missing.c_str()});
  expectUsageError("--screenshot shot.jpg", {"--screenshot", "shot.jpg", ".png"});
  expectUsageError("--screenshots /proc/sandphys-shots", {"--screenshots", "/proc/sandphys-shots"});
}

TEST(ScreenshotCli, TinyRunWritesAPngOfTheRequestedSize) {
  const std::filesystem::path out =
      std::filesystem::path(SANDPHYS_RENDER_TEST_OUTPUT) / "cli_shot.png";
  const std::filesystem::path sequence =
      std::filesystem::path(SANDPHYS_RENDER_TEST_OUTPUT) / "cli_sequence";
  std::filesystem::remove(out);
  std::filesystem::remove_all(sequence);
  // A small cylinder (15 d) and 32 granules: the cost is the floor's setup and one frame.
  const ProcessResult result = runSamples(
      "--quiet --scene cylinder-pile --batch 4 2 4 --param radius=15 --param first-drop=2 "
      "--frames 2 --size 96x64 --screenshot '" +
      out.string() + "' --screenshots '" + sequence.string() + "' --every 1");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  int w = 0, h = 0, channels = 0;
  ASSERT_TRUE(stbi_info(out.c_str(), &w, &h, &channels)) << out;
  EXPECT_EQ(w, 96);
  EXPECT_EQ(h, 64);
  EXPECT_TRUE(std::filesystem::exists(sequence / "frame_000001.png"));
  EXPECT_TRUE(std::filesystem::exists(sequence / "frame_000002.png"));
  EXPECT_FALSE(std::filesystem::exists(sequence / "frame_000003.png"));
}

}  // namespace
}  // namespace sandphys::testing
