// The windowed samples app under a virtual X server (CTest runs this program through xvfb-run):
// every registered scene opens its window, runs a few frames, writes a screenshot through its
// own key binding (F, pressed by the SANDPHYS_VIEWER_KEYS hook, so the real key handler runs)
// and exits with status 0.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "runner/process.h"
#include "scenes/registry.h"

namespace sandphys {
namespace {

namespace fs = std::filesystem;

// The app's windows are small and their scenes tiny: llvmpipe does every pixel and every
// substep on the CPU, and a test should take seconds.
constexpr const char* kWindow = "--size 320x240";
constexpr const char* kShortFrames = "--frame-dt 0.004";

std::string quoted(const std::string& text) {
  return "'" + text + "'";
}

// Command line parameters that keep a scene small: every block of granules at most 4 per axis.
// Parameters of 0 (e.g. "no bed") stay 0.
std::string smallSceneParameters(const scenes::SceneEntry& entry) {
  std::unique_ptr<scenes::Scene> scene = entry.create();
  std::string arguments;
  for (const scenes::SceneParameter& parameter : scene->parameters()) {
    if (const auto* counts = std::get_if<scenes::Count3*>(&parameter.value)) {
      std::string value;
      for (std::uint32_t count : **counts) {
        const auto small = static_cast<std::uint32_t>(
            std::max<double>(parameter.min, std::min<std::uint32_t>(count, 4)));
        if (!value.empty()) value += ',';
        value += std::to_string(small);
      }
      arguments += " --param " + parameter.name + "=" + value;
    }
  }
  return arguments;
}

struct Image {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;
};

Image readPng(const fs::path& path) {
  Image image;
  int channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
  if (pixels) {
    image.rgb.assign(pixels, pixels + static_cast<std::size_t>(image.width) * image.height * 3);
    stbi_image_free(pixels);
  }
  return image;
}

// Standard deviation of the luminance, 0..255: a blank or single-colour frame has none.
double luminanceSpread(const Image& image) {
  double sum = 0.0, sumSquares = 0.0;
  const std::size_t count = image.rgb.size() / 3;
  for (std::size_t i = 0; i < count; ++i) {
    const double y =
        0.2126 * image.rgb[3 * i] + 0.7152 * image.rgb[3 * i + 1] + 0.0722 * image.rgb[3 * i + 2];
    sum += y;
    sumSquares += y * y;
  }
  if (count == 0) return 0.0;
  const double mean = sum / static_cast<double>(count);
  return std::sqrt(std::max(0.0, sumSquares / static_cast<double>(count) - mean * mean));
}

void expectPicture(const fs::path& path, int width, int height) {
  ASSERT_TRUE(fs::exists(path)) << path;
  const Image image = readPng(path);
  ASSERT_EQ(image.width, width) << path;
  ASSERT_EQ(image.height, height) << path;
  EXPECT_GT(luminanceSpread(image), 5.0) << path << " is (nearly) uniform";
}

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::path(SANDPHYS_VIEWER_TEST_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

testing::ProcessResult runViewer(const fs::path& dir, const std::string& keys,
                                 const std::string& arguments) {
  return testing::runCommand("cd " + quoted(dir.string()) + " && SANDPHYS_VIEWER_KEYS=" +
                             quoted(keys) + " " + quoted(SANDPHYS_SAMPLES_EXE) + " " + arguments);
}

class ViewerScene : public ::testing::TestWithParam<const scenes::SceneEntry*> {};

TEST_P(ViewerScene, RunsAndTakesAKeyScreenshot) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  const scenes::SceneEntry& entry = *GetParam();
  const std::string name(entry.name);
  const fs::path dir = freshDirectory(name);
  const testing::ProcessResult result =
      runViewer(dir, "F@3",
                "--scene " + name + smallSceneParameters(entry) + " --frames 5 " + kShortFrames +
                    " " + kWindow + " --screenshot " + quoted((dir / "last.png").string()));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  expectPicture(dir / (name + "-000003.png"), 320, 240);
  expectPicture(dir / "last.png", 320, 240);
}

std::vector<const scenes::SceneEntry*> registeredScenes() {
  std::vector<const scenes::SceneEntry*> entries;
  for (const scenes::SceneEntry& entry : scenes::sceneRegistry()) entries.push_back(&entry);
  return entries;
}

std::string sceneTestName(const ::testing::TestParamInfo<const scenes::SceneEntry*>& info) {
  std::string name(info.param->name);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ViewerScene, ::testing::ValuesIn(registeredScenes()),
                         sceneTestName);

// The sand tools run while their keys are held (pour with P, push with B), pause, step and
// restart keep the loop going, --screenshots/--every writes its sequence, and Esc ends the run
// with status 0 long before the frame limit, writing the last frame (frame 12, the 13th).
TEST(ViewerTools, PourPushAndQuitWithEscape) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  const fs::path dir = freshDirectory("tools");
  const testing::ProcessResult result =
      runViewer(dir, "P@1-6,B@2-7,S@8,SPACE@9,S@10,R@11,ESC@12",
                std::string("--scene box-drop --param block=3,2,3 --frames 1000 ") + kShortFrames +
                    " " + kWindow + " --screenshot " + quoted((dir / "last.png").string()) +
                    " --screenshots " + quoted((dir / "sequence").string()) + " --every 4");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  // Mesa gives GLX windows the same OpenGL 4.5 core context as the headless EGL path.
  EXPECT_NE(result.output.find("4.5 (Core Profile)"), std::string::npos) << result.output;
  expectPicture(dir / "last.png", 320, 240);
  for (const char* image : {"frame_000004.png", "frame_000008.png", "frame_000012.png"}) {
    expectPicture(dir / "sequence" / image, 320, 240);
  }
  EXPECT_FALSE(fs::exists(dir / "sequence" / "frame_000016.png"));
}

// Without a display the viewer fails with a message, not a crash.
TEST(ViewerErrors, NoDisplayIsAClearError) {
  const fs::path dir = freshDirectory("no_display");
  const testing::ProcessResult result =
      testing::runCommand("cd " + quoted(dir.string()) + " && env -u DISPLAY -u WAYLAND_DISPLAY " +
                          quoted(SANDPHYS_SAMPLES_EXE) + " --scene box-drop --frames 1");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_NE(result.output.find("GLFW"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace sandphys
