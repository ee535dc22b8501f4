// The windowed samples app under a virtual X server (CTest runs this program through xvfb-run):
// every registered scene opens its window, runs a few frames, writes a screenshot through its
// own key binding (F, pressed by the SANDPHYS_VIEWER_KEYS hook, so the real key handler runs)
// and exits with status 0; --panel-in-screenshots puts the panel into the pictures and leaves
// the scene as it was.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "runner/process.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"
#include "support/every_scene.h"

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

// Command line parameters that give a scene its test size (scenes::useTestSize): those it
// changes.
std::string smallSceneParameters(const scenes::SceneEntry& entry) {
  std::unique_ptr<scenes::Scene> defaults = entry.create();
  std::unique_ptr<scenes::Scene> scene = entry.create();
  scenes::useTestSize(*scene);
  const std::vector<scenes::SceneParameter> before = defaults->parameters();
  const std::vector<scenes::SceneParameter> after = scene->parameters();
  std::string arguments;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const std::string value = scenes::formatSceneParameter(after[i]);
    if (value == scenes::formatSceneParameter(before[i])) continue;
    arguments += " --param " + after[i].name + "=" + quoted(value);
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

// The window opens on the scene's own view (Scene::view), clear of the panel: in the first
// picture, panel included, the sand shows beside the panel's place, and hardly any of it under
// that place (it is framed in the rest of the window). Sand is told by its colour: the
// renderer's grains are tan to orange (red over green over blue, red under half the sum), the
// colliders, stone and metal bodies, panel and sky grey or blue, wooden bodies redder (red over
// half the sum): the avalanche's blocks show in wood beside the panel too. (Each body's own
// pixels and colour: BodySurfaces in tests/render.)
TEST_P(ViewerScene, OpensOnItsSandBesideThePanel) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  const scenes::SceneEntry& entry = *GetParam();
  const std::string name(entry.name);
  const fs::path dir = freshDirectory(name + "_view");
  constexpr int kWidth = 640, kHeight = 400;
  // The panel's place at first use: (8, 8), a quarter of the window wide (viewer/panel.h).
  constexpr int kPanelRight = 8 + kWidth / 4 + 4;
  const testing::ProcessResult result =
      runViewer(dir, "",
                // Frames of 0.02 s run whole (no frame budget): a pour has begun by the last.
                "--scene " + name + smallSceneParameters(entry) +
                    " --frames 8 --frame-dt 0.02 --frame-budget 0 --size " +
                    std::to_string(kWidth) + "x" + std::to_string(kHeight) +
                    " --panel-in-screenshots --screenshot " + quoted((dir / "last.png").string()));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const Image image = readPng(dir / "last.png");
  ASSERT_EQ(image.width, kWidth);
  long beside = 0, under = 0, wood = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const unsigned char* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      const bool warm = p[0] > p[1] + 12 && p[1] > p[2] + 12;
      const bool sand = warm && p[0] > 90 && 2 * p[0] < p[0] + p[1] + p[2];
      if (sand) ++(x < kPanelRight ? under : beside);
      if (warm && p[0] > 40 && 2 * p[0] > p[0] + p[1] + p[2] && x >= kPanelRight) ++wood;
    }
  }
  std::printf("%s: %ld sand pixels beside the panel, %ld under its place; %ld wood pixels\n",
              name.c_str(), beside, under, wood);
  EXPECT_GT(beside, 200) << "no sand beside the panel";
  EXPECT_LT(under, beside / 10) << "the sand is framed under the panel";
  if (name == "avalanche") {
    EXPECT_GT(wood, 100) << "the wooden blocks do not show beside the panel";
  } else {
    EXPECT_LT(wood, 20) << "wood where the scene has none";
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ViewerScene, ::testing::ValuesIn(testing::registeredScenes()),
                         testing::sceneTestName);

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

// Records a small box-drop run in the window to `file`, driven by `keys` (the sand tools held, Esc
// to end it), with a snapshot every `snapshotEvery` frames.
testing::ProcessResult recordInWindow(const fs::path& dir, const fs::path& file,
                                      const std::string& keys, int snapshotEvery) {
  return runViewer(dir, keys,
                   std::string("--scene box-drop --param block=3,2,3 --frames 1000 ") +
                       kShortFrames + " " + kWindow + " --snapshot-every " +
                       std::to_string(snapshotEvery) + " --record " + quoted(file.string()));
}

// A run in the window, recorded with the sand tools in use and the frame pacer choosing each
// frame's duration, replays bit for bit headless from its file (docs/recording.md).
TEST(ViewerRecording, ReplaysHeadlessBitForBit) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  const fs::path dir = freshDirectory("recording");
  const fs::path file = dir / "window.sprec";
  const testing::ProcessResult run = recordInWindow(dir, file, "P@1-6,B@3-8,ESC@10", 4);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const Recording recording = readRecording(file);
  const std::string frames = std::to_string(recording.frames.size());
  ASSERT_GE(recording.frames.size(), 9u);
  EXPECT_NE(run.output.find("recorded " + frames + " frames to"), std::string::npos) << run.output;
  EXPECT_EQ(*recording.setting("tools"), "sand-tools");
  // The tools were held: their input is in the frames, and they poured.
  EXPECT_FALSE(recording.frames[3].events.empty());
  EXPECT_TRUE(recording.frames.back().events.empty());
  EXPECT_GT(recording.snapshots.back().bodies.size(), recording.snapshots.front().bodies.size());

  const testing::ProcessResult replay =
      testing::runCommand(quoted(SANDPHYS_SAMPLES_EXE) + " --replay " + quoted(file.string()));
  EXPECT_EQ(replay.exitCode, 0) << replay.output;
  EXPECT_NE(replay.output.find(frames + " frames bit-identical"), std::string::npos)
      << replay.output;
}

// --play: a recording made in the window (the sand tools held) plays with its timeline driven by
// keys: Space pauses at frame 3, Left shows the snapshot of frame 0, Right comes back to frame 3,
// Left again, S steps on from the snapshot (re-simulating from the start), R goes back to the
// start and Space plays to the end. Every frame re-simulated matches the recording. A copy whose
// frame 5 hash was changed (and its checksum made anew) plays to the end and fails, naming the
// frame.
TEST(ViewerPlayback, PlaysScrubsAndFlagsAFrameThatDiffers) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  const fs::path dir = freshDirectory("playback");
  const fs::path file = dir / "window.sprec";
  const testing::ProcessResult run = recordInWindow(dir, file, "P@1-4,B@2-5,ESC@8", 3);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const Recording recording = readRecording(file);
  const std::uint64_t frames = recording.frames.size();
  ASSERT_GE(frames, 7u);
  const std::string played = "frame " + std::to_string(frames) + " of " + std::to_string(frames) +
                             " shown, " + std::to_string(frames) + " frames re-simulated";

  const testing::ProcessResult play =
      runViewer(dir, "SPACE@3,LEFT@4,RIGHT@5,LEFT@7,S@8,R@10,SPACE@11,ESC@40",
                std::string("--play ") + quoted(file.string()) + " " + kWindow + " --screenshot " +
                    quoted((dir / "played.png").string()));
  ASSERT_EQ(play.exitCode, 0) << play.output;
  EXPECT_NE(play.output.find(played + ", every one as recorded"), std::string::npos) << play.output;
  expectPicture(dir / "played.png", 320, 240);

  const fs::path changed = dir / "changed.sprec";
  {
    RecordingWriter writer(changed, recording.settings);
    for (RecordedFrame frame : recording.frames) {
      if (frame.steps == recording.frames[4].steps) frame.stateHash ^= 1u;
      writer.addFrame(frame);
    }
    for (const WorldSnapshot& snapshot : recording.snapshots) writer.addSnapshot(snapshot);
    writer.finish(recording.wallSeconds);
  }
  const testing::ProcessResult differs =
      runViewer(dir, "ESC@30", std::string("--play ") + quoted(changed.string()) + " " + kWindow);
  EXPECT_EQ(differs.exitCode, 1) << differs.output;
  EXPECT_NE(differs.output.find("differs from the recording at frame 5: state hash"),
            std::string::npos)
      << differs.output;
  EXPECT_NE(differs.output.find(played + ", not as recorded"), std::string::npos) << differs.output;
}

// A rectangle of pixels, [x0, x1) × [y0, y1), rows from the top of the image.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  int area() const { return std::max(0, x1 - x0) * std::max(0, y1 - y0); }
};

bool samePixel(const Image& a, const Image& b, std::size_t pixel) {
  return a.rgb[3 * pixel] == b.rgb[3 * pixel] && a.rgb[3 * pixel + 1] == b.rgb[3 * pixel + 1] &&
         a.rgb[3 * pixel + 2] == b.rgb[3 * pixel + 2];
}

// Where two images of one size differ: the bounding box and the count of differing pixels.
struct Difference {
  PixelBox box;
  long pixels = 0;
};

Difference difference(const Image& a, const Image& b) {
  Difference result;
  result.box = {a.width, a.height, 0, 0};
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (samePixel(a, b, static_cast<std::size_t>(y) * a.width + x)) continue;
      ++result.pixels;
      result.box.x0 = std::min(result.box.x0, x);
      result.box.y0 = std::min(result.box.y0, y);
      result.box.x1 = std::max(result.box.x1, x + 1);
      result.box.y1 = std::max(result.box.y1, y + 1);
    }
  }
  return result;
}

long differingOutside(const Image& a, const Image& b, const PixelBox& box) {
  long count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (!box.contains(x, y) && !samePixel(a, b, static_cast<std::size_t>(y) * a.width + x)) {
        ++count;
      }
    }
  }
  return count;
}

// What the pixels of a box look like. ImGui's dark style is a near-black grey window (about 60%
// of the panel's pixels), dark blue fields and headers (most of the rest) and light grey text.
struct BoxLook {
  double dark = 0.0;      // fraction with luminance < 80 of 255
  double darkGrey = 0.0;  // fraction dark and with channels within 40 of each other
  long bright = 0;        // pixels with luminance > 180: text
};

BoxLook look(const Image& image, const PixelBox& box) {
  BoxLook result;
  long dark = 0, darkGrey = 0;
  for (int y = box.y0; y < box.y1; ++y) {
    for (int x = box.x0; x < box.x1; ++x) {
      const unsigned char* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      const double luminance = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      if (luminance < 80.0) ++dark;
      if (luminance < 80.0 && spread < 40) ++darkGrey;
      if (luminance > 180.0) ++result.bright;
    }
  }
  if (box.area() > 0) {
    result.dark = static_cast<double>(dark) / box.area();
    result.darkGrey = static_cast<double>(darkGrey) / box.area();
  }
  return result;
}

// The same short run twice, each frame simulating its whole frame dt (--frame-budget 0) so that
// both worlds and pictures match, once with --panel-in-screenshots: the pictures (the one of
// --screenshot and the one of the F key) differ exactly where the panel is, a window a quarter
// of the window wide at (8, 8) drawn in ImGui's dark style, and nowhere else.
TEST(ViewerScreenshots, PanelInScreenshotsAddsThePanelAndLeavesTheScene) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run through xvfb-run (CTest does)";
  constexpr int kWidth = 960, kHeight = 600;
  // The panel's place and width at first use (viewer/panel.h: a quarter of the window, at most
  // 430 px); its height follows its contents, at most the window's.
  constexpr int kPanelX = 8, kPanelY = 8, kPanelWidth = kWidth / 4;
  // Edges are allowed this much play, px (ImGui's border and rounding).
  constexpr int kEdgeSlack = 4;
  const fs::path dir = freshDirectory("panel_in_screenshots");
  const std::string run = "--scene box-drop --param block=3,2,3 --frames 6 " +
                          std::string(kShortFrames) + " --frame-budget 0 --size " +
                          std::to_string(kWidth) + "x" + std::to_string(kHeight);
  for (const char* variant : {"scene", "window"}) {
    const fs::path variantDir = dir / variant;
    fs::create_directories(variantDir);
    const std::string panel = variant == std::string("window") ? " --panel-in-screenshots" : "";
    const testing::ProcessResult result =
        runViewer(variantDir, "F@3",
                  run + panel + " --screenshot " + quoted((variantDir / "last.png").string()));
    ASSERT_EQ(result.exitCode, 0) << result.output;
  }

  for (const char* picture : {"last.png", "box-drop-000003.png"}) {
    SCOPED_TRACE(picture);
    const Image scene = readPng(dir / "scene" / picture);
    const Image window = readPng(dir / "window" / picture);
    ASSERT_EQ(scene.width, kWidth);
    ASSERT_EQ(scene.height, kHeight);
    ASSERT_EQ(window.width, kWidth);
    ASSERT_EQ(window.height, kHeight);
    EXPECT_GT(luminanceSpread(scene), 5.0) << "the scene-only picture is (nearly) uniform";

    const Difference diff = difference(scene, window);
    const PixelBox& box = diff.box;
    std::printf("%s: %ld pixels differ, in x %d..%d, y %d..%d\n", picture, diff.pixels, box.x0,
                box.x1, box.y0, box.y1);
    ASSERT_GT(diff.pixels, 0) << "the panel is not in the picture";
    EXPECT_NEAR(box.x0, kPanelX, kEdgeSlack);
    EXPECT_NEAR(box.y0, kPanelY, kEdgeSlack);
    EXPECT_NEAR(box.x1 - box.x0, kPanelWidth, kEdgeSlack);
    EXPECT_GE(box.y1 - box.y0, 200) << "a panel shorter than its first section";
    EXPECT_LE(box.y1, kHeight);
    // The panel's window covers its box: nearly every pixel in it differs from the scene.
    EXPECT_GT(static_cast<double>(diff.pixels) / box.area(), 0.9);

    // Outside the panel's place the scene is untouched (the count is exact, so this also holds
    // when the box above came out wrong).
    const PixelBox panelPlace{0, 0, kPanelX + kPanelWidth + kEdgeSlack, kHeight};
    EXPECT_LE(differingOutside(scene, window, panelPlace), 4);

    const BoxLook panel = look(window, box);
    const BoxLook under = look(scene, box);
    std::printf(
        "%s: panel %.0f%% dark, %.0f%% dark grey, %ld bright pixels; the scene there %.0f%% "
        "dark\n",
        picture, 100.0 * panel.dark, 100.0 * panel.darkGrey, panel.bright, 100.0 * under.dark);
    EXPECT_GT(panel.dark, 0.85) << "not ImGui's dark window";
    EXPECT_GT(panel.darkGrey, 0.45) << "not ImGui's grey window background";
    EXPECT_GT(panel.bright, 2000) << "no text on the panel";
    EXPECT_LT(under.dark, 0.3) << "the scene itself is dark there: the look proves nothing";
  }
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
