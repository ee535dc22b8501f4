#include "viewer/window.h"

#include <GL/glew.h>
// GLEW must come before GLFW, which would otherwise pull in the system GL header.
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace sandphys::viewer {

namespace {

std::string glfwErrorText() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  if (code == GLFW_NO_ERROR) return "no reason given";
  return description ? description : "GLFW error " + std::to_string(code);
}

}  // namespace

Window::Window(Extent size, const std::string& title) {
  if (!glfwInit()) {
    throw std::runtime_error(
        "cannot initialise GLFW (is DISPLAY set? use --headless without a "
        "display): " +
        glfwErrorText());
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  m_window = glfwCreateWindow(size.width, size.height, title.c_str(), nullptr, nullptr);
  if (!m_window) {
    const std::string reason = glfwErrorText();
    glfwTerminate();
    throw std::runtime_error("cannot open a window with an OpenGL 4.5 core context: " + reason);
  }
  glfwMakeContextCurrent(m_window);
  // The library checks the version and the compute shader support when it adopts the context;
  // GLEW is loaded here because the viewer itself calls GL (screenshots, clearing).
  glewExperimental = GL_TRUE;
  const GLenum glew = glewInit();
  if (glew != GLEW_OK) {
    glfwDestroyWindow(m_window);
    glfwTerminate();
    throw std::runtime_error(std::string("cannot load OpenGL with GLEW: ") +
                             reinterpret_cast<const char*>(glewGetErrorString(glew)));
  }
  setVsync(true);
}

Window::~Window() {
  glfwDestroyWindow(m_window);
  glfwTerminate();
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(m_window) != 0;
}

void Window::requestClose() {
  glfwSetWindowShouldClose(m_window, GLFW_TRUE);
}

Extent Window::framebufferSize() const {
  Extent extent;
  glfwGetFramebufferSize(m_window, &extent.width, &extent.height);
  return extent;
}

Extent Window::windowSize() const {
  Extent extent;
  glfwGetWindowSize(m_window, &extent.width, &extent.height);
  return extent;
}

void Window::setVsync(bool on) {
  glfwSwapInterval(on ? 1 : 0);
  m_vsync = on;
}

void Window::setTitle(const std::string& title) {
  glfwSetWindowTitle(m_window, title.c_str());
}

void Window::swapBuffers() {
  glfwSwapBuffers(m_window);
}

}  // namespace sandphys::viewer
