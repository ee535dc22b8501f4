#pragma once

#include <algorithm>

#include <string>

#include "scenes/registry.h"
#include "viewer/frame_stats.h"
#include "viewer/session.h"

namespace sandphys::viewer {

/// What the viewer state looks like to the panel this frame.
struct PanelView {
  bool paused = false;
  bool vsync = true;
  bool panelInScreenshots = false;  ///< screenshots show the panel too
  std::string gpu;                  ///< GpuContext::description
  std::string lastScreenshot;       ///< path of the last PNG written, or empty
  std::string message;              ///< one line of feedback (e.g. a failed screenshot), or empty
};

/// What the user asked for in the panel this frame; the app applies it after the frame.
struct PanelRequests {
  const scenes::SceneEntry* switchTo = nullptr;
  bool restart = false;
  bool togglePause = false;
  bool step = false;
  bool screenshot = false;
  bool toggleVsync = false;
};

/// The Dear ImGui panel: scene menu and parameters, frame budget and render quality (applied at
/// once), material and time step (applied on restart), statistics and live plots. Edits to the
/// scene's parameters and the controls go straight into the session and take effect at the next
/// restart.
/// Left and top margin of the panel's window, px.
inline constexpr float kPanelMargin = 8.0f;
/// The panel's width when it first shows in a window `windowWidth` px wide: a quarter of it, at
/// most 430 px; the user may drag it wider.
inline float panelWidth(float windowWidth) {
  return std::min(430.0f, 0.25f * windowWidth);
}

class Panel {
 public:
  /// Draws the panel inside the current ImGui frame.
  PanelRequests draw(Session& session, const FrameStats& stats, const StatsHistory& history,
                     const PanelView& view);

 private:
  void drawScene(Session& session, const PanelView& view, PanelRequests& requests);
  void drawPacing(Session& session, const FrameStats& stats);
  void drawParameters(Session& session);
  void drawControls(Session& session);
  void drawStats(const Session& session, const FrameStats& stats, const StatsHistory& history);
  void drawHelp(const PanelView& view);

  std::string m_parameterError;
};

}  // namespace sandphys::viewer
