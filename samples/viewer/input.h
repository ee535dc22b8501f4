#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace sandphys::viewer {

/// What a key press asks the viewer to do once.
enum class Command {
  TogglePause,  ///< Space
  Step,         ///< S: one frame while paused
  Restart,      ///< R: rebuild the scene on a fresh World
  Screenshot,   ///< F: write the next frame to a PNG
  Quit,         ///< Esc
  HomeView,     ///< Home: the scene's own view again (Scene::view)
  TogglePanel,  ///< Tab: hide or show the panel
  /// Left and Right arrows, --play: the recorded snapshot before or after the frame shown.
  PreviousSnapshot,
  NextSnapshot,
};

/// Mouse and key state gathered over one frame, consumed by the camera and the sand tools.
struct FrameInput {
  std::vector<Command> commands;
  float orbitX = 0.0f, orbitY = 0.0f;    ///< drag with the left button, window pixels
  float panX = 0.0f, panY = 0.0f;        ///< drag with the middle button or Shift+left, pixels
  float zoomSteps = 0.0f;                ///< wheel notches, positive towards the scene
  bool pour = false;                     ///< right button or P held: pour sand under the cursor
  bool push = false;                     ///< Ctrl+left button or B held: push with the sphere
  float cursorX = 0.0f, cursorY = 0.0f;  ///< window pixels from the top left
};

/// Turns GLFW's events into FrameInput. Its callbacks are installed before Dear ImGui's, which
/// chain to them; events that the panel wants (a click on a widget, typing into a field) are
/// ignored here.
class Input {
 public:
  explicit Input(GLFWwindow* window);
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  /// Whether the panel takes the mouse and the keyboard this frame (ImGuiIO::WantCapture*).
  void setPanelCapture(bool mouse, bool keyboard);
  /// The frame's input; resets the per-frame sums and commands.
  FrameInput takeFrame();

  /// Every key event goes through here, from GLFW or from the test KeyScript alike.
  void onKey(int key, int action, int mods);
  void onMouseButton(int button, int action, int mods);
  void onCursor(double x, double y);
  void onScroll(double dy);

 private:
  FrameInput m_frame;
  bool m_panelMouse = false;
  bool m_panelKeyboard = false;
  bool m_orbiting = false;
  bool m_panning = false;
  bool m_pushingMouse = false;
  bool m_pouringMouse = false;
  bool m_pourKey = false;
  bool m_pushKey = false;
  bool m_shift = false;
  bool m_haveCursor = false;
  double m_lastX = 0.0, m_lastY = 0.0;
};

/// Key presses scripted for tests through the environment variable SANDPHYS_VIEWER_KEYS, so
/// that a test drives the real key handler: "F@5" presses F at frame 5 and releases it at frame
/// 6; "P@2-9" holds P from frame 2 to frame 9; entries are separated by commas. Keys are single
/// letters or digits, SPACE, ESC, ENTER, LEFT, RIGHT. Frames count from 0.
class KeyScript {
 public:
  /// Reads SANDPHYS_VIEWER_KEYS; empty when it is not set. Throws std::runtime_error naming the
  /// variable and the bad entry.
  static KeyScript fromEnvironment();
  /// Parses `text` (the format above).
  static KeyScript parse(const std::string& text);

  /// A key going down or up at the start of a frame.
  struct Event {
    std::uint64_t frame = 0;  ///< counted from 0
    int key = 0;              ///< GLFW key code (GLFW_KEY_*)
    bool press = true;        ///< true: down (GLFW_PRESS); false: up (GLFW_RELEASE)
    bool operator==(const Event&) const = default;
  };

  bool empty() const { return m_events.empty(); }
  /// Each entry's press and then its release, in the order of the entries: "F@5" is F down at
  /// frame 5 and up at 6, "P@2-9" P down at 2 and up at 10.
  const std::vector<Event>& events() const { return m_events; }
  /// Feeds the presses and releases due at `frame` to `input`.
  void apply(std::uint64_t frame, Input& input) const;

 private:
  std::vector<Event> m_events;
};

}  // namespace sandphys::viewer
