// The viewer's pieces that need no window: key scripts, camera control, tool capacities, plots,
// the frame pacer and the viewer's command-line flags.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/cli.h"
#include "app/sand_tools.h"
#include "viewer/camera_control.h"
#include "viewer/frame_pacer.h"
#include "viewer/frame_stats.h"
#include "viewer/input.h"

namespace sandphys::viewer {

// How GoogleTest prints a scripted key event when a comparison fails (found by argument-dependent
// lookup, so outside the unnamed namespace).
void PrintTo(const KeyScript::Event& event, std::ostream* out) {
  *out << "{frame " << event.frame << ", key " << event.key << (event.press ? ", down}" : ", up}");
}

namespace {

using samples::SandTools;

using KeyEvent = KeyScript::Event;
using KeyEvents = std::vector<KeyEvent>;

// What a script parses into: each entry's key down and key up, in the order of the entries.
TEST(KeyScript, ParsesPressesAndHoldsIntoKeysDownAndUp) {
  // A press is down at its frame and up at the next.
  EXPECT_EQ(KeyScript::parse("F@5").events(),
            (KeyEvents{{5, GLFW_KEY_F, true}, {6, GLFW_KEY_F, false}}));
  // A hold is down from its first frame and up after its last; a hold of one frame is a press.
  EXPECT_EQ(KeyScript::parse("P@2-9").events(),
            (KeyEvents{{2, GLFW_KEY_P, true}, {10, GLFW_KEY_P, false}}));
  EXPECT_EQ(KeyScript::parse("S@4-4").events(),
            (KeyEvents{{4, GLFW_KEY_S, true}, {5, GLFW_KEY_S, false}}));
  // Entries keep their order; letters in either case, digits and named keys; empty entries are
  // skipped.
  EXPECT_EQ(KeyScript::parse("P@2-9,b@3,,ESC@12,SPACE@0,7@1,").events(),
            (KeyEvents{{2, GLFW_KEY_P, true},
                       {10, GLFW_KEY_P, false},
                       {3, GLFW_KEY_B, true},
                       {4, GLFW_KEY_B, false},
                       {12, GLFW_KEY_ESCAPE, true},
                       {13, GLFW_KEY_ESCAPE, false},
                       {0, GLFW_KEY_SPACE, true},
                       {1, GLFW_KEY_SPACE, false},
                       {1, GLFW_KEY_7, true},
                       {2, GLFW_KEY_7, false}}));
  const std::pair<const char*, int> named[] = {
      {"A@0", GLFW_KEY_A},       {"z@0", GLFW_KEY_Z},         {"0@0", GLFW_KEY_0},
      {"9@0", GLFW_KEY_9},       {"ENTER@0", GLFW_KEY_ENTER}, {"ESCAPE@0", GLFW_KEY_ESCAPE},
      {"LEFT@0", GLFW_KEY_LEFT}, {"RIGHT@0", GLFW_KEY_RIGHT}};
  for (const auto& [entry, key] : named) {
    EXPECT_EQ(KeyScript::parse(entry).events(), (KeyEvents{{0, key, true}, {1, key, false}}))
        << entry;
  }
  EXPECT_TRUE(KeyScript::parse("").empty());
  EXPECT_TRUE(KeyScript::parse(",,").empty());
}

TEST(KeyScript, RefusesBadEntriesNamingThem) {
  for (const char* bad : {"F", "F@", "F@x", "F@5-2", "WHAT@3", "F@-1"}) {
    try {
      (void)KeyScript::parse(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("SANDPHYS_VIEWER_KEYS"), std::string::npos);
      EXPECT_NE(std::string(error.what()).find(bad), std::string::npos) << error.what();
    }
  }
}

TEST(CameraControl, RayThroughTheCentreHitsTheTarget) {
  render::Camera camera;
  camera.target = {0.3f, 0.1f, -0.2f};
  camera.distance = 2.0f;
  const Ray ray = camera_control::rayThrough(camera, 400.0f, 300.0f, 800.0f, 600.0f);
  const Eigen::Vector3f toTarget = camera.target - ray.origin;
  // Distance of the target from the ray, m: the centre pixel looks straight at it.
  EXPECT_LT((toTarget - toTarget.dot(ray.direction) * ray.direction).norm(), 1e-5f);
  const std::optional<Eigen::Vector3f> hit = hitHorizontalPlane(ray, camera.target.y());
  ASSERT_TRUE(hit.has_value());
  EXPECT_LT((*hit - camera.target).norm(), 1e-4f);
}

TEST(CameraControl, CornerRaysSpanTheFieldOfView) {
  render::Camera camera;
  const Ray top = camera_control::rayThrough(camera, 400.0f, 0.0f, 800.0f, 600.0f);
  const Ray bottom = camera_control::rayThrough(camera, 400.0f, 600.0f, 800.0f, 600.0f);
  EXPECT_NEAR(std::acos(top.direction.dot(bottom.direction)), camera.fovY, 1e-4f);
  EXPECT_GT(top.direction.y(), bottom.direction.y());  // window y grows downwards
}

TEST(CameraControl, NoHitWhenLookingAwayFromThePlane) {
  const Ray up{{0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  EXPECT_FALSE(hitHorizontalPlane(up, 0.0f).has_value());
  const Ray level{{0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  EXPECT_FALSE(hitHorizontalPlane(level, 0.0f).has_value());
}

TEST(CameraControl, OrbitKeepsThePitchOffThePoles) {
  render::Camera camera;
  camera_control::orbit(camera, 0.0f, 1.0e5f);
  EXPECT_FLOAT_EQ(camera.pitch, camera_control::kMaxPitch);
  camera_control::orbit(camera, 0.0f, -1.0e5f);
  EXPECT_FLOAT_EQ(camera.pitch, -camera_control::kMaxPitch);
}

TEST(CameraControl, PanMovesTheTargetAcrossTheView) {
  render::Camera camera;
  const Eigen::Vector3f before = camera.target;
  const Eigen::Vector3f forward = (camera.target - camera.eye()).normalized();
  camera_control::pan(camera, 50.0f, -20.0f, 600.0f);
  const Eigen::Vector3f moved = camera.target - before;
  EXPECT_GT(moved.norm(), 0.0f);
  EXPECT_NEAR(moved.dot(forward), 0.0f, 1e-5f);  // in the image plane, no zoom
  // A drag of the window's full height moves the scene by the view's height at the target.
  render::Camera tall;
  const Eigen::Vector3f start = tall.target;
  camera_control::pan(tall, 0.0f, 600.0f, 600.0f);
  EXPECT_NEAR((tall.target - start).norm(), 2.0f * tall.distance * std::tan(0.5f * tall.fovY),
              1e-4f);
}

TEST(CameraControl, ZoomIsGeometricAndBounded) {
  render::Camera camera;
  camera.distance = 2.0f;
  camera_control::zoom(camera, 1.0f);
  const float once = camera.distance;
  EXPECT_LT(once, 2.0f);
  camera_control::zoom(camera, -1.0f);
  EXPECT_NEAR(camera.distance, 2.0f, 1e-5f);
  camera_control::zoom(camera, 1.0e4f);
  EXPECT_FLOAT_EQ(camera.distance, camera_control::kMinDistance);
}

TEST(SandTools, CapacityCoversThePourBudgetAndTheSphere) {
  WorldSettings granulesOnly;
  granulesOnly.maxBodies = 100;  // maxParticles 0: four per body
  const WorldSettings grown = SandTools::withToolCapacity(granulesOnly);
  EXPECT_EQ(grown.maxBodies, 100u + SandTools::kPourGranules + 1u);
  // Ball of radius 6 d on a lattice of spacing d: about 4/3 π 6³ ≈ 905 particles.
  EXPECT_GT(grown.maxParticles, 400u + 4u * SandTools::kPourGranules + 800u);
  EXPECT_LT(grown.maxParticles, 400u + 4u * SandTools::kPourGranules + 1000u);

  WorldSettings withFloor;
  withFloor.maxBodies = 101;
  withFloor.maxParticles = 5000;  // a rough floor's particles on top of the granules
  EXPECT_GT(SandTools::withToolCapacity(withFloor).maxParticles,
            5000u + 4u * SandTools::kPourGranules);
}

TEST(PlotHistory, KeepsTheNewestValuesInOrder) {
  PlotHistory history;
  for (int i = 0; i < static_cast<int>(PlotHistory::kLength) + 10; ++i) {
    history.push(static_cast<float>(i));
  }
  ASSERT_EQ(history.size(), static_cast<int>(PlotHistory::kLength));
  EXPECT_FLOAT_EQ(history.data()[0], 10.0f);
  EXPECT_FLOAT_EQ(history.latest(), static_cast<float>(PlotHistory::kLength + 9));
  EXPECT_FLOAT_EQ(history.max(), history.latest());
}

using render::RenderQuality;

// Feeds `frames` draws of `renderMs` each, numbered on from `draws`, as the viewer does: the
// renderer's times arrive one draw late.
void drawFrames(FramePacer& pacer, double renderMs, int frames, std::uint64_t& draws) {
  for (int i = 0; i < frames; ++i) {
    ++draws;
    if (draws > 1) pacer.recordDraw(renderMs, draws - 1, draws);
  }
}

TEST(FramePacer, WithoutABudgetEveryFrameRunsItsWholeFrameDt) {
  FramePacer pacer;
  EXPECT_FALSE(pacer.pacing());
  EXPECT_EQ(pacer.substepsFor(253), 253u);
  pacer.recordStep(253 * 30.0, 253);
  EXPECT_EQ(pacer.substepsFor(253), 253u);
  EXPECT_EQ(pacer.quality(), RenderQuality::High);  // auto without a budget
}

TEST(FramePacer, StartsWithOneSubstepAndFillsTheBudgetBesideTheRendering) {
  FramePacer pacer(50.0, RenderQuality::Medium);
  EXPECT_EQ(pacer.substepsFor(253), 1u);  // nothing measured yet
  pacer.recordStep(4.0, 1);
  std::uint64_t draws = 0;
  drawFrames(pacer, 10.0, 3, draws);
  // (50 - 10) ms / 4 ms per substep.
  EXPECT_EQ(pacer.substepsFor(253), 10u);
  EXPECT_EQ(pacer.substepsFor(7), 7u);  // never more than the whole frame
  // Steps dearer than the room left still run one substep: the simulation must go on.
  pacer.forgetStepCost();
  pacer.recordStep(300.0, 1);
  EXPECT_EQ(pacer.substepsFor(253), 1u);
  drawFrames(pacer, 80.0, 1, draws);  // rendering alone over the budget
  EXPECT_EQ(pacer.substepsFor(253), 1u);
}

TEST(FramePacer, SmoothsTheCostOfASubstep) {
  FramePacer pacer(100.0, RenderQuality::Low);
  pacer.recordStep(20.0, 10);  // 2 ms each: the first measurement is taken as it is
  EXPECT_DOUBLE_EQ(pacer.msPerSubstep(), 2.0);
  pacer.recordStep(60.0, 10);  // one frame at 6 ms moves the estimate by kSmoothing of the way
  EXPECT_DOUBLE_EQ(pacer.msPerSubstep(), 2.0 + FramePacer::kSmoothing * 4.0);
  pacer.recordStep(5.0, 0);  // a step that ran no substep
  pacer.recordStep(std::numeric_limits<double>::quiet_NaN(), 3);
  EXPECT_DOUBLE_EQ(pacer.msPerSubstep(), 2.0 + FramePacer::kSmoothing * 4.0);
  for (int i = 0; i < 60; ++i) pacer.recordStep(60.0, 10);
  EXPECT_NEAR(pacer.msPerSubstep(), 6.0, 1e-6);
  EXPECT_EQ(pacer.substepsFor(253), 16u);  // 100 ms / 6 ms
}

TEST(FramePacer, ABudgetOfZeroOrNonsenseIsOff) {
  FramePacer pacer(50.0, std::nullopt);
  EXPECT_TRUE(pacer.pacing());
  pacer.setBudgetMs(0.0);
  EXPECT_FALSE(pacer.pacing());
  pacer.setBudgetMs(-3.0);
  EXPECT_FALSE(pacer.pacing());
  pacer.setBudgetMs(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(pacer.pacing());
}

TEST(FramePacer, AutoQualityStepsDownAfterSeveralSlowFramesOnly) {
  FramePacer pacer(50.0, std::nullopt);
  ASSERT_EQ(pacer.quality(), RenderQuality::High);
  std::uint64_t draws = 0;
  // One slow frame among fast ones changes nothing.
  drawFrames(pacer, 40.0, FramePacer::kFramesToLower - 1, draws);
  drawFrames(pacer, 20.0, 1, draws);
  drawFrames(pacer, 40.0, FramePacer::kFramesToLower - 1, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::High);
  // Render time over half the budget in enough consecutive frames: one step down.
  drawFrames(pacer, 40.0, 2, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Medium);
  // Draws already made at high quality, measured after the change, do not count against medium.
  const std::uint64_t changedAt = draws;
  for (std::uint64_t draw = changedAt - 1; draw <= changedAt; ++draw) {
    for (int i = 0; i < FramePacer::kFramesToLower; ++i) pacer.recordDraw(40.0, draw, changedAt);
  }
  EXPECT_EQ(pacer.quality(), RenderQuality::Medium);
  // Still too slow at medium: down to low, and no further.
  drawFrames(pacer, 40.0, FramePacer::kFramesToLower + 1, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
  drawFrames(pacer, 40.0, 10 * FramePacer::kFramesToLower, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
}

TEST(FramePacer, AutoQualityStepsUpOnlyWhenFarBelowTheBudget) {
  FramePacer pacer(50.0, std::nullopt);
  std::uint64_t draws = 0;
  drawFrames(pacer, 40.0, FramePacer::kFramesToLower + 1, draws);
  drawFrames(pacer, 40.0, FramePacer::kFramesToLower + 1, draws);
  ASSERT_EQ(pacer.quality(), RenderQuality::Low);
  // Between the two thresholds (7.5 and 25 ms of 50): stays, however long.
  drawFrames(pacer, 12.0, 10 * FramePacer::kFramesToRaise, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
  // Far below: one step up after kFramesToRaise frames, not before.
  drawFrames(pacer, 5.0, FramePacer::kFramesToRaise - 1, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
  drawFrames(pacer, 5.0, 2, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::Medium);
}

// A preset that costs 2.5 times the next lower one, rendered at several budgets: auto settles
// on one preset and stays there.
TEST(FramePacer, AutoQualityDoesNotOscillate) {
  for (const double lowMs : {1.0, 4.0, 9.0, 14.0, 30.0}) {
    FramePacer pacer(50.0, std::nullopt);
    std::uint64_t draws = 0;
    int changes = 0;
    RenderQuality last = pacer.quality();
    for (int frame = 0; frame < 2000; ++frame) {
      const int level = static_cast<int>(pacer.quality());
      drawFrames(pacer, lowMs * std::pow(2.5, level), 1, draws);
      if (pacer.quality() != last) ++changes;
      last = pacer.quality();
    }
    EXPECT_LE(changes, 2) << "low preset at " << lowMs << " ms";
  }
}

TEST(FramePacer, FixedQualityStaysAndAutoGoesOnFromIt) {
  FramePacer pacer(50.0, RenderQuality::High);
  std::uint64_t draws = 0;
  drawFrames(pacer, 45.0, 100, draws);
  EXPECT_EQ(pacer.quality(), RenderQuality::High);
  pacer.setFixedQuality(RenderQuality::Low);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
  pacer.setFixedQuality(std::nullopt);
  EXPECT_EQ(pacer.quality(), RenderQuality::Low);
  EXPECT_FALSE(pacer.fixedQuality().has_value());
}

// The flags are parsed in process: parseCommandLine touches no GPU.
struct Parsed {
  std::optional<int> exitCode;
  samples::RunOptions options;
  std::string errors;
};

Parsed parse(std::vector<std::string> arguments) {
  arguments.insert(arguments.begin(), "sandphys-samples");
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  Parsed parsed;
  ::testing::internal::CaptureStderr();
  parsed.exitCode =
      samples::parseCommandLine(static_cast<int>(argv.size()), argv.data(), parsed.options);
  parsed.errors = ::testing::internal::GetCapturedStderr();
  return parsed;
}

void expectUsageError(const std::vector<std::string>& arguments,
                      const std::vector<std::string>& named) {
  const Parsed parsed = parse(arguments);
  EXPECT_EQ(parsed.exitCode, samples::kExitUsage) << parsed.errors;
  for (const std::string& text : named) {
    EXPECT_NE(parsed.errors.find(text), std::string::npos)
        << "'" << text << "' not named in: " << parsed.errors;
  }
}

TEST(ViewerFlags, Defaults) {
  const Parsed windowed = parse({});
  ASSERT_FALSE(windowed.exitCode) << windowed.errors;
  EXPECT_EQ(windowed.options.frameBudgetMs, 50.0);
  EXPECT_FALSE(windowed.options.quality.has_value());  // auto
  EXPECT_FALSE(windowed.options.panelInScreenshots);
}

TEST(ViewerFlags, AcceptsBudgetsQualitiesAndPanelScreenshots) {
  const Parsed parsed =
      parse({"--frame-budget", "0", "--quality", "medium", "--panel-in-screenshots"});
  ASSERT_FALSE(parsed.exitCode) << parsed.errors;
  EXPECT_EQ(parsed.options.frameBudgetMs, 0.0);
  EXPECT_EQ(parsed.options.quality, RenderQuality::Medium);
  EXPECT_TRUE(parsed.options.panelInScreenshots);
  EXPECT_EQ(parse({"--frame-budget", "33.5"}).options.frameBudgetMs, 33.5);
  EXPECT_EQ(parse({"--frame-budget", "10000"}).options.frameBudgetMs, 10000.0);
  EXPECT_FALSE(parse({"--quality", "auto"}).options.quality.has_value());
  const Parsed headless = parse({"--headless", "--quality", "low"});
  ASSERT_FALSE(headless.exitCode) << headless.errors;
  EXPECT_EQ(headless.options.quality, RenderQuality::Low);
}

TEST(ViewerFlags, RefusesBadBudgetsNamingThem) {
  for (const char* bad : {"-5", "10000.5", "nan", "inf", "1e3", "fast", ""}) {
    expectUsageError({"--frame-budget", bad}, {"--frame-budget", bad, "0..10000"});
  }
}

TEST(ViewerFlags, RefusesUnknownQualitiesAndAutoHeadless) {
  expectUsageError({"--quality", "ultra"}, {"--quality", "ultra", "auto, low, medium or high"});
  expectUsageError({"--headless", "--quality", "auto"}, {"--quality auto", "headless"});
}

TEST(ViewerFlags, WindowOnlyFlagsAreRefusedHeadless) {
  expectUsageError({"--headless", "--frame-budget", "20"}, {"--frame-budget 20", "--headless"});
  expectUsageError({"--headless", "--panel-in-screenshots"},
                   {"--panel-in-screenshots", "--headless"});
}

TEST(ViewerFlags, RollingFrictionReachesTheScenesWorld) {
  const Parsed parsed = parse({"--scene", "box-drop", "--headless", "--rolling-friction", "0.2"});
  ASSERT_FALSE(parsed.exitCode) << parsed.errors;
  ASSERT_TRUE(parsed.options.scene);
  EXPECT_EQ(parsed.options.scene->settings().material.rollingFriction, 0.2f);
  const Parsed none = parse({"--scene", "box-drop", "--headless"});
  ASSERT_FALSE(none.exitCode) << none.errors;
  EXPECT_EQ(none.options.scene->settings().material.rollingFriction, 0.0f);
  expectUsageError({"--rolling-friction", "-1"}, {"--rolling-friction", "-1"});
}

}  // namespace
}  // namespace sandphys::viewer
