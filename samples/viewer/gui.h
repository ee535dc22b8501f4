#pragma once

struct GLFWwindow;

namespace sandphys::viewer {

/// Dear ImGui on the window's GLFW events and OpenGL 3 backend (Debian's libimgui carries both).
/// Create it after Input: ImGui's GLFW callbacks chain to the ones already installed.
class Gui {
 public:
  explicit Gui(GLFWwindow* window);
  ~Gui();
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;

  /// Starts an ImGui frame; widgets may be submitted until render().
  void beginFrame();
  /// Draws the frame's widgets over whatever the default framebuffer holds.
  void render();
  /// Whether the panel wants the mouse / the keyboard (the cursor is over it, a field has focus).
  bool wantsMouse() const;
  bool wantsKeyboard() const;
};

}  // namespace sandphys::viewer
