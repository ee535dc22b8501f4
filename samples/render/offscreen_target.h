#pragma once

#include <cstdint>
#include <vector>

namespace sandphys::render {

/// A framebuffer of its own (RGBA8 colour, 32-bit float depth) for rendering without a window,
/// e.g. headless screenshots through EGL. Needs a current OpenGL 4.5 context for its whole life.
class OffscreenTarget {
 public:
  /// Throws InvalidArgument for a size outside 1..16384 and GpuError if the framebuffer is
  /// incomplete.
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// Binds it as the draw and read framebuffer (Renderer::draw then draws into it).
  void bind() const;
  /// The GL framebuffer name.
  unsigned framebuffer() const { return m_framebuffer; }
  int width() const { return m_width; }
  int height() const { return m_height; }
  /// The colour, 4 bytes per pixel, rows from the top of the image down (as image files store
  /// them). Sync point: waits for the GPU.
  std::vector<std::uint8_t> readRgba() const;

 private:
  int m_width = 0;
  int m_height = 0;
  unsigned m_framebuffer = 0;
  unsigned m_colour = 0;
  unsigned m_depth = 0;
};

}  // namespace sandphys::render
