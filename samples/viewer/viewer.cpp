// The viewer's frame loop: input, simulation, drawing, panel, screenshots. The pieces live in
// their own files (window, input, camera control, session, panel, gui, screenshot; the sand tools
// in app/sand_tools.h, where a headless replay can use them too).
#include "viewer/viewer.h"

#include <GL/glew.h>
// GLEW must come before GLFW, which would otherwise pull in the system GL header.
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <vector>

#include "render/render_quality.h"
#include "render/renderer.h"
#include "viewer/camera_control.h"
#include "viewer/frame_stats.h"
#include "viewer/gui.h"
#include "viewer/input.h"
#include "viewer/panel.h"
#include "viewer/playback_panel.h"
#include "viewer/player.h"
#include "viewer/screenshot.h"
#include "viewer/session.h"
#include "viewer/window.h"

namespace sandphys::samples {

namespace {

using Clock = std::chrono::steady_clock;
using namespace sandphys::viewer;

Extent windowExtent(const RunOptions& options) {
  return {options.size.width, options.size.height};
}

std::string windowTitle(const scenes::Scene& scene) {
  return "sandphys - " + std::string(scene.name());
}

// F writes <scene>-<frame>.png into the --screenshots folder when one was given, else into the
// working directory.
std::filesystem::path keyScreenshotPath(const RunOptions& options, std::string_view scene,
                                        std::uint64_t frame) {
  char name[96];
  std::snprintf(name, sizeof name, "%.*s-%06llu.png", static_cast<int>(scene.size()), scene.data(),
                static_cast<unsigned long long>(frame));
  return options.screenshotDir.empty() ? std::filesystem::path(name) : options.screenshotDir / name;
}

// The image sequence of --screenshots/--every, named like the headless runner's.
std::filesystem::path sequencePath(const RunOptions& options, std::uint64_t frame) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(frame));
  return options.screenshotDir / name;
}

// What the whole run did, printed at its end: frames per second and how much simulation each
// frame got are what the frame budget trades against each other.
struct RunTotals {
  std::uint64_t frames = 0;
  std::uint64_t steppedFrames = 0;
  double wallSeconds = 0.0;
  double stepMilliseconds = 0.0;
  std::uint64_t substeps = 0;
  std::uint64_t fullSubsteps = 0;
  double simulatedSeconds = 0.0;
  double frameDtSeconds = 0.0;  // simulated time had every stepped frame run its whole frame dt
  double renderMilliseconds = 0.0;

  void add(const FrameStats& stats, double frameDt) {
    ++frames;
    wallSeconds += stats.frameMilliseconds * 1e-3;
    renderMilliseconds += stats.render.totalMs;
    if (!stats.stepped) return;
    ++steppedFrames;
    stepMilliseconds += stats.stepMilliseconds;
    substeps += stats.report.substeps;
    fullSubsteps += stats.fullSubsteps;
    simulatedSeconds += stats.report.simulatedTime;
    frameDtSeconds += frameDt;
  }

  void print(std::ostream& out, const FrameStats& last, render::RenderQuality quality,
             double budgetMs) const {
    if (frames == 0) return;
    const double stepped = static_cast<double>(std::max<std::uint64_t>(steppedFrames, 1));
    char budget[32] = "off";
    if (budgetMs > 0.0) std::snprintf(budget, sizeof budget, "%g ms", budgetMs);
    const std::string_view preset = render::renderQualityName(quality);
    char line[512];
    std::snprintf(line, sizeof line,
                  "sandphys-samples: %llu frames in %.2f s (%.2f frames/s, budget %s): %.1f of "
                  "%.0f substeps per frame (x%.3g of real time), step %.1f ms, render %.1f ms GPU "
                  "per frame; last frame %.*s %dx%d\n",
                  static_cast<unsigned long long>(frames), wallSeconds,
                  static_cast<double>(frames) / std::max(wallSeconds, 1e-9), budget,
                  static_cast<double>(substeps) / stepped,
                  static_cast<double>(fullSubsteps) / stepped,
                  simulatedSeconds / std::max(frameDtSeconds, 1e-12), stepMilliseconds / stepped,
                  renderMilliseconds / static_cast<double>(frames), static_cast<int>(preset.size()),
                  preset.data(), last.render.renderWidth, last.render.renderHeight);
    out << line;
  }
};

// The scene's own view (Scene::view) of what it holds now, clear of the panel's strip on the
// left when the panel shows. One read-back of the bodies (a sync point), on demand only.
render::Camera framingCamera(const scenes::Scene& scene, const World& world, Extent framebuffer,
                             bool panelShown) {
  const float aspect = framebuffer.height > 0 ? static_cast<float>(framebuffer.width) /
                                                    static_cast<float>(framebuffer.height)
                                              : 16.0f / 9.0f;
  const float width = static_cast<float>(std::max(framebuffer.width, 1));
  const float covered = panelShown ? (kPanelMargin + panelWidth(width)) / width : 0.0f;
  return render::Camera::framing(scene.view(scenes::contentsOf(scene, world)), aspect, covered);
}

// The viewer's state between frames and the frame itself: a live Session, or a Player of a
// recording (--play).
class ViewerLoop {
 public:
  ViewerLoop(RunOptions& options, Window& window)
      : m_options(options),
        m_window(window),
        m_gpu(GpuContext::fromCurrentContext()),
        m_input(window.handle()),
        m_gui(window.handle()),
        m_script(KeyScript::fromEnvironment()) {
    m_view.gpu = m_gpu.description();
    if (!m_options.quiet) std::cerr << "sandphys-samples: viewer on " << m_view.gpu << '\n';
    const FramePacer pacer(options.frameBudgetMs, options.quality);
    if (!m_options.playPath.empty()) {
      m_player = std::make_unique<Player>(m_gpu, m_options.playPath, pacer);
    } else {
      m_session =
          std::make_unique<Session>(m_gpu, std::move(options.scene), options.frameDt, pacer);
    }
    if (!m_options.recordPath.empty()) {
      m_session->startRecording(m_options.recordPath, m_options.snapshotEvery);
    }
    home();
    m_window.setTitle(windowTitle(scene()));
    if (!m_script.empty()) {
      // Scripted runs (tests) act on the middle of the window wherever the pointer was.
      const Extent size = m_window.windowSize();
      glfwSetCursorPos(m_window.handle(), 0.5 * size.width, 0.5 * size.height);
      m_input.onCursor(0.5 * size.width, 0.5 * size.height);
    }
  }

  /// Whether a screenshot could not be written.
  bool screenshotFailed() const { return m_screenshotFailed; }
  /// Whether a played recording's re-simulation differed from it.
  bool playbackDiffered() const { return m_player && m_player->playback().mismatch(); }

  int run() {
    if (m_options.framesGiven && m_options.frames == 0) return kExitOk;
    Clock::time_point frameStart = Clock::now();
    for (std::uint64_t frame = 0;; ++frame) {
      const bool last = runFrame(frame);
      const Clock::time_point now = Clock::now();
      m_stats.frameMilliseconds =
          std::chrono::duration<double, std::milli>(now - frameStart).count();
      m_stats.simPerWall = m_stats.stepped ? m_stats.report.simulatedTime /
                                                 std::max(m_stats.frameMilliseconds * 1e-3, 1e-9)
                                           : 0.0;
      frameStart = now;
      m_history.push(m_stats);
      m_totals.add(m_stats,
                   m_session ? m_session->applied().frameDt : m_stats.report.simulatedTime);
      if (last) {
        if (!m_options.quiet) {
          m_totals.print(std::cerr, m_stats, pacer().quality(), pacer().budgetMs());
          if (m_player) printPlayed();
        }
        return kExitOk;
      }
    }
  }

 private:
  // One frame; true when it was the last.
  bool runFrame(std::uint64_t frame) {
    glfwPollEvents();
    m_script.apply(frame, m_input);
    m_input.setPanelCapture(m_gui.wantsMouse(), m_gui.wantsKeyboard());
    const FrameInput input = m_input.takeFrame();

    bool quit = m_window.shouldClose();
    bool screenshot = m_pendingScreenshot;
    bool step = m_pendingStep;
    m_pendingScreenshot = m_pendingStep = false;
    for (const Command command : input.commands) {
      switch (command) {
        case Command::TogglePause:
          togglePause();
          break;
        case Command::Step:
          step = true;
          break;
        case Command::Restart:
          restart();
          break;
        case Command::PreviousSnapshot:
        case Command::NextSnapshot:
          if (m_player) jumpToSnapshot(command == Command::NextSnapshot);
          break;
        case Command::Screenshot:
          screenshot = true;
          break;
        case Command::Quit:
          quit = true;
          break;
        case Command::HomeView:
          home();
          break;
        case Command::TogglePanel:
          m_panelShown = !m_panelShown;
          break;
      }
    }
    camera_control::orbit(m_camera, input.orbitX, input.orbitY);
    const Extent windowSize = m_window.windowSize();
    camera_control::pan(m_camera, input.panX, input.panY, static_cast<float>(windowSize.height));
    camera_control::zoom(m_camera, input.zoomSteps);

    m_stats.stepped = false;
    if (m_player) {
      m_player->frame(!m_paused && !m_scrubbing, step, m_stats);
      reportMismatch();
    } else if (!m_paused || step) {
      const Ray ray = camera_control::rayThrough(m_camera, input.cursorX, input.cursorY,
                                                 static_cast<float>(windowSize.width),
                                                 static_cast<float>(windowSize.height));
      m_session->stepFrame(input.pour, input.push, ray, m_stats);
    }

    const Extent size = m_window.framebufferSize();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size.width, size.height);
    if (size.width > 0 && size.height > 0) {
      render::applyRenderQuality(pacer().quality(), m_renderer.settings());
      // Playing a recording there is no panel toggle: sleeping granules are tinted.
      m_renderer.settings().tintSleeping = !m_session || m_session->controls().tintSleeping;
      m_renderer.settings().bodyParticles = m_session && m_session->controls().bodyParticles;
      m_renderer.draw(world(), m_camera, scene().bounds(), size.width, size.height, surfaces());
      ++m_draws;
      const render::RenderStats& renderStats = m_renderer.stats();
      pacer().recordDraw(renderStats.totalMs, renderStats.frame, m_draws);
      m_stats.render = renderStats;
    }

    const bool last = quit || (m_options.framesGiven && frame + 1 >= m_options.frames);
    m_screenshots.clear();
    if (screenshot) {
      m_screenshots.push_back(keyScreenshotPath(m_options, scene().name(), frame));
    }
    // Frames count from 1 here: image k·every shows the world after k·every frames.
    if (!m_options.screenshotDir.empty() && m_options.every > 0 &&
        (frame + 1) % m_options.every == 0) {
      m_screenshots.push_back(sequencePath(m_options, frame + 1));
    }
    if (last && !m_options.screenshotPath.empty()) {
      m_screenshots.push_back(m_options.screenshotPath);
    }

    // Screenshots show the scene alone unless --panel-in-screenshots: then they are taken once
    // the panel is drawn over it, and show the whole window.
    if (!m_options.panelInScreenshots) saveScreenshots(size);
    m_gui.beginFrame();
    m_view.paused = m_paused;
    m_view.vsync = m_window.vsync();
    m_view.panelInScreenshots = m_options.panelInScreenshots;
    // The panel's requests apply once the frame is shown.
    if (!m_panelShown) {
      present(size);
    } else if (m_player) {
      const PlaybackRequests requests = drawPlaybackPanel(*m_player, m_stats, m_history, m_view);
      present(size);
      apply(requests);
    } else {
      const PanelRequests requests = m_panel.draw(*m_session, m_stats, m_history, m_view);
      present(size);
      apply(requests);
    }
    return last;
  }

  // Draws the panel's ImGui frame over the scene and swaps; screenshots that show the panel are
  // taken in between.
  void present(Extent size) {
    m_gui.render();
    if (m_options.panelInScreenshots) saveScreenshots(size);
    m_window.swapBuffers();
  }

  // Home: the camera back on the scene's own view of what it holds now.
  void home() {
    m_camera = framingCamera(scene(), world(), m_window.framebufferSize(), m_panelShown);
  }

  World& world() { return m_player ? m_player->world() : m_session->world(); }
  const scenes::Scene& scene() const { return m_player ? m_player->scene() : m_session->scene(); }
  FramePacer& pacer() { return m_player ? m_player->pacer() : m_session->pacer(); }

  // The scene's surfaces and, once the push tool has joined the World, its ball.
  std::span<const scenes::SceneSurface> surfaces() {
    const scenes::SceneSurface* ball = m_player ? nullptr : m_session->tools().surface();
    if (!ball) return scene().surfaces();
    m_surfaces.assign(scene().surfaces().begin(), scene().surfaces().end());
    m_surfaces.push_back(*ball);
    return m_surfaces;
  }

  // Space: pause or go on; a recording played to its end starts again.
  void togglePause() {
    if (m_player && m_paused && m_player->atEnd()) m_player->playback().scrubTo(0);
    m_paused = !m_paused;
  }

  // R: a live scene is built again; a recording goes back to its start.
  void restart() {
    if (m_player) {
      m_player->playback().scrubTo(0);
    } else {
      m_session->restart();
    }
    m_history.clear();
    m_view.message.clear();
  }

  void jumpToSnapshot(bool next) {
    samples::Playback& playback = m_player->playback();
    const std::optional<std::uint64_t> frame =
        next ? playback.snapshotAfter() : playback.snapshotBefore();
    if (frame) playback.scrubTo(*frame);
  }

  // A difference is printed once, when found; the panel keeps showing it.
  void reportMismatch() {
    const auto& mismatch = m_player->playback().mismatch();
    if (!mismatch || m_mismatchReported) return;
    m_mismatchReported = true;
    std::cerr << "sandphys-samples: play of '" << m_player->file().string()
              << "' differs from the recording at " << mismatch->what << '\n';
  }

  void printPlayed() const {
    const samples::Playback& playback = m_player->playback();
    std::cerr << "sandphys-samples: played '" << m_player->file().string() << "' ("
              << scene().name() << "): frame " << playback.shownFrame() << " of "
              << playback.frames() << " shown, " << playback.checkedFrames()
              << " frames re-simulated"
              << (playback.mismatch() ? ", not as recorded" : ", every one as recorded") << '\n';
  }

  void apply(const PlaybackRequests& requests) {
    samples::Playback& playback = m_player->playback();
    m_scrubbing = requests.scrubbing;
    if (requests.scrubTo) playback.scrubTo(*requests.scrubTo);
    if (requests.toStart) restart();
    if (requests.previousSnapshot) jumpToSnapshot(false);
    if (requests.nextSnapshot) jumpToSnapshot(true);
    if (requests.togglePause) togglePause();
    if (requests.step) m_pendingStep = true;
    if (requests.screenshot) m_pendingScreenshot = true;
    if (requests.toggleVsync) m_window.setVsync(!m_window.vsync());
  }

  void apply(const PanelRequests& requests) {
    if (requests.switchTo) {
      m_session->switchScene(*requests.switchTo);
      home();
      m_window.setTitle(windowTitle(scene()));
      m_history.clear();
      m_view.message.clear();
    }
    if (requests.restart) restart();
    if (requests.togglePause) togglePause();
    if (requests.step) m_pendingStep = true;
    if (requests.screenshot) m_pendingScreenshot = true;
    if (requests.toggleVsync) m_window.setVsync(!m_window.vsync());
  }

  void saveScreenshots(Extent size) {
    for (const std::filesystem::path& path : m_screenshots) saveScreenshot(path, size);
  }

  void saveScreenshot(const std::filesystem::path& path, Extent size) {
    try {
      writeBackBufferPng(path, size.width, size.height);
      m_view.lastScreenshot = path.string();
      if (!m_options.quiet) std::cerr << "sandphys-samples: wrote " << path.string() << '\n';
    } catch (const Error& error) {
      // A failed screenshot should not end an interactive session; the panel shows why.
      m_view.message = error.what();
      std::cerr << "sandphys-samples: " << error.what() << '\n';
      m_screenshotFailed = true;
    }
  }

  RunOptions& m_options;
  Window& m_window;
  GpuContext m_gpu;
  Input m_input;
  Gui m_gui;
  KeyScript m_script;
  std::unique_ptr<Session> m_session;
  bool m_panelShown = true;  // Tab hides it
  std::unique_ptr<Player> m_player;
  render::Renderer m_renderer;
  render::Camera m_camera;
  Panel m_panel;
  FrameStats m_stats;
  StatsHistory m_history;
  RunTotals m_totals;
  PanelView m_view;
  // This frame's screenshot paths, kept to be written before or after the panel is drawn.
  std::vector<std::filesystem::path> m_screenshots;
  std::uint64_t m_draws = 0;
  std::vector<scenes::SceneSurface> m_surfaces;  // surfaces() with the tool's ball
  bool m_paused = false;
  bool m_pendingStep = false;
  bool m_pendingScreenshot = false;
  bool m_screenshotFailed = false;
  bool m_scrubbing = false;
  bool m_mismatchReported = false;
};

}  // namespace

int runViewer(RunOptions& options) {
  Window window(windowExtent(options),
                "sandphys - " + (options.playPath.empty() ? options.sceneName
                                                          : options.playPath.filename().string()));
  ViewerLoop loop(options, window);
  const int status = loop.run();
  // A run asked to write a screenshot fails when it could not, as the headless runner does; a
  // played recording that did not re-simulate as recorded fails as --replay does.
  if (status == kExitOk && (loop.screenshotFailed() || loop.playbackDiffered()))
    return kExitFailure;
  return status;
}

}  // namespace sandphys::samples
