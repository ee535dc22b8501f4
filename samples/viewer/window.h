#pragma once

#include <string>

struct GLFWwindow;

namespace sandphys::viewer {

/// Width and height in pixels.
struct Extent {
  int width = 0;
  int height = 0;
};

/// The GLFW window and its OpenGL 4.5 core context, current on the creating thread, with GLEW
/// loaded. One per process: it initialises GLFW and terminates it again.
class Window {
 public:
  /// Opens a resizable window of `size` (window pixels). Throws std::runtime_error with GLFW's
  /// own reason when there is no display or no OpenGL 4.5 core context.
  Window(Extent size, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return m_window; }
  bool shouldClose() const;
  void requestClose();
  /// Size of the drawable in pixels (differs from windowSize on high-DPI screens).
  Extent framebufferSize() const;
  /// Size in window coordinates, the unit of cursor positions.
  Extent windowSize() const;
  /// Synchronises buffer swaps to the display refresh (on) or not (off).
  void setVsync(bool on);
  bool vsync() const { return m_vsync; }
  void setTitle(const std::string& title);
  void swapBuffers();

 private:
  GLFWwindow* m_window = nullptr;
  bool m_vsync = true;
};

}  // namespace sandphys::viewer
