#include "viewer/input.h"

#include <GLFW/glfw3.h>

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace sandphys::viewer {

namespace {

Input& inputOf(GLFWwindow* window) {
  return *static_cast<Input*>(glfwGetWindowUserPointer(window));
}

}  // namespace

Input::Input(GLFWwindow* window) {
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int /*scancode*/, int action, int mods) {
    inputOf(w).onKey(key, action, mods);
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
    inputOf(w).onMouseButton(button, action, mods);
  });
  glfwSetCursorPosCallback(window,
                           [](GLFWwindow* w, double x, double y) { inputOf(w).onCursor(x, y); });
  glfwSetScrollCallback(window,
                        [](GLFWwindow* w, double /*dx*/, double dy) { inputOf(w).onScroll(dy); });
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  onCursor(x, y);
}

void Input::setPanelCapture(bool mouse, bool keyboard) {
  m_panelMouse = mouse;
  m_panelKeyboard = keyboard;
}

FrameInput Input::takeFrame() {
  FrameInput frame = std::move(m_frame);
  frame.pour = m_pourKey || m_pouringMouse;
  frame.push = m_pushKey || m_pushingMouse;
  m_frame = FrameInput{};
  m_frame.cursorX = frame.cursorX;
  m_frame.cursorY = frame.cursorY;
  return frame;
}

void Input::onKey(int key, int action, int mods) {
  m_shift = (mods & GLFW_MOD_SHIFT) != 0;
  if (action == GLFW_RELEASE) {
    // Releases always count, so that a hold that began before the panel took focus ends.
    if (key == GLFW_KEY_P) m_pourKey = false;
    if (key == GLFW_KEY_B) m_pushKey = false;
    return;
  }
  if (m_panelKeyboard) return;
  if (action == GLFW_PRESS) {
    switch (key) {
      case GLFW_KEY_SPACE:
        m_frame.commands.push_back(Command::TogglePause);
        break;
      case GLFW_KEY_S:
        m_frame.commands.push_back(Command::Step);
        break;
      case GLFW_KEY_R:
        m_frame.commands.push_back(Command::Restart);
        break;
      case GLFW_KEY_F:
        m_frame.commands.push_back(Command::Screenshot);
        break;
      case GLFW_KEY_ESCAPE:
        m_frame.commands.push_back(Command::Quit);
        break;
      case GLFW_KEY_HOME:
        m_frame.commands.push_back(Command::HomeView);
        break;
      case GLFW_KEY_TAB:
        m_frame.commands.push_back(Command::TogglePanel);
        break;
      case GLFW_KEY_LEFT:
        m_frame.commands.push_back(Command::PreviousSnapshot);
        break;
      case GLFW_KEY_RIGHT:
        m_frame.commands.push_back(Command::NextSnapshot);
        break;
      case GLFW_KEY_P:
        m_pourKey = true;
        break;
      case GLFW_KEY_B:
        m_pushKey = true;
        break;
      default:
        break;
    }
  } else if (action == GLFW_REPEAT && key == GLFW_KEY_S) {
    m_frame.commands.push_back(Command::Step);  // hold S to step repeatedly
  }
}

void Input::onMouseButton(int button, int action, int mods) {
  m_shift = (mods & GLFW_MOD_SHIFT) != 0;
  if (action == GLFW_RELEASE) {
    if (button == GLFW_MOUSE_BUTTON_LEFT) m_orbiting = m_pushingMouse = m_panning = false;
    if (button == GLFW_MOUSE_BUTTON_MIDDLE) m_panning = false;
    if (button == GLFW_MOUSE_BUTTON_RIGHT) m_pouringMouse = false;
    return;
  }
  if (m_panelMouse) return;
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    if (mods & GLFW_MOD_CONTROL) {
      m_pushingMouse = true;
    } else if (mods & GLFW_MOD_SHIFT) {
      m_panning = true;
    } else {
      m_orbiting = true;
    }
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    m_panning = true;
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    m_pouringMouse = true;
  }
}

void Input::onCursor(double x, double y) {
  if (m_haveCursor) {
    const float dx = static_cast<float>(x - m_lastX);
    const float dy = static_cast<float>(y - m_lastY);
    if (m_panning) {
      m_frame.panX += dx;
      m_frame.panY += dy;
    } else if (m_orbiting) {
      m_frame.orbitX += dx;
      m_frame.orbitY += dy;
    }
  }
  m_haveCursor = true;
  m_lastX = x;
  m_lastY = y;
  m_frame.cursorX = static_cast<float>(x);
  m_frame.cursorY = static_cast<float>(y);
}

void Input::onScroll(double dy) {
  if (m_panelMouse) return;
  m_frame.zoomSteps += static_cast<float>(dy);
}

namespace {

constexpr const char* kKeyScriptVariable = "SANDPHYS_VIEWER_KEYS";

[[noreturn]] void badEntry(std::string_view entry, std::string_view why) {
  throw std::runtime_error(std::string(kKeyScriptVariable) + ": entry '" + std::string(entry) +
                           "' " + std::string(why) +
                           " (expected KEY@FRAME or KEY@FIRST-LAST, e.g. F@5,P@2-9)");
}

int keyCode(std::string_view name, std::string_view entry) {
  if (name.size() == 1) {
    const char c = name[0];
    if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
    if (c >= 'a' && c <= 'z') return GLFW_KEY_A + (c - 'a');
    if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
  }
  if (name == "SPACE") return GLFW_KEY_SPACE;
  if (name == "ESC" || name == "ESCAPE") return GLFW_KEY_ESCAPE;
  if (name == "ENTER") return GLFW_KEY_ENTER;
  if (name == "LEFT") return GLFW_KEY_LEFT;
  if (name == "RIGHT") return GLFW_KEY_RIGHT;
  badEntry(entry, "names an unknown key");
}

std::uint64_t frameNumber(std::string_view text, std::string_view entry) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) badEntry(entry, "has a bad frame number");
  return value;
}

}  // namespace

KeyScript KeyScript::fromEnvironment() {
  const char* text = std::getenv(kKeyScriptVariable);
  return text ? parse(text) : KeyScript{};
}

KeyScript KeyScript::parse(const std::string& text) {
  KeyScript script;
  std::string_view rest = text;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view entry = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    if (entry.empty()) continue;
    const std::size_t at = entry.find('@');
    if (at == std::string_view::npos) badEntry(entry, "has no '@'");
    const int key = keyCode(entry.substr(0, at), entry);
    const std::string_view frames = entry.substr(at + 1);
    const std::size_t dash = frames.find('-');
    const std::uint64_t first = frameNumber(frames.substr(0, dash), entry);
    const std::uint64_t last =
        dash == std::string_view::npos ? first : frameNumber(frames.substr(dash + 1), entry);
    if (last < first) badEntry(entry, "ends before it starts");
    script.m_events.push_back({first, key, true});
    script.m_events.push_back({last + 1, key, false});
  }
  return script;
}

void KeyScript::apply(std::uint64_t frame, Input& input) const {
  for (const Event& event : m_events) {
    if (event.frame == frame) input.onKey(event.key, event.press ? GLFW_PRESS : GLFW_RELEASE, 0);
  }
}

}  // namespace sandphys::viewer
