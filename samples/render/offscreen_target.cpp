#include "render/offscreen_target.h"

#include <GL/glew.h>

#include <cstring>
#include <string>

#include <sandphys/error.h>

namespace sandphys::render {

namespace {
constexpr int kMaxSize = 16384;
}

OffscreenTarget::OffscreenTarget(int width, int height) : m_width(width), m_height(height) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
    throw InvalidArgument("OffscreenTarget size " + std::to_string(width) + "x" +
                          std::to_string(height) + ": each side must be in 1.." +
                          std::to_string(kMaxSize));
  }
  glCreateRenderbuffers(1, &m_colour);
  glNamedRenderbufferStorage(m_colour, GL_RGBA8, width, height);
  glCreateRenderbuffers(1, &m_depth);
  glNamedRenderbufferStorage(m_depth, GL_DEPTH_COMPONENT32F, width, height);
  glCreateFramebuffers(1, &m_framebuffer);
  glNamedFramebufferRenderbuffer(m_framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_colour);
  glNamedFramebufferRenderbuffer(m_framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m_depth);
  const GLenum status = glCheckNamedFramebufferStatus(m_framebuffer, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &m_framebuffer);
    glDeleteRenderbuffers(1, &m_colour);
    glDeleteRenderbuffers(1, &m_depth);
    throw GpuError("offscreen framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                   " is incomplete (status " + std::to_string(status) + ")");
  }
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteFramebuffers(1, &m_framebuffer);
  glDeleteRenderbuffers(1, &m_colour);
  glDeleteRenderbuffers(1, &m_depth);
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer);
}

std::vector<std::uint8_t> OffscreenTarget::readRgba() const {
  const std::size_t row = std::size_t(m_width) * 4;
  std::vector<std::uint8_t> pixels(row * std::size_t(m_height));
  glNamedFramebufferReadBuffer(m_framebuffer, GL_COLOR_ATTACHMENT0);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m_framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m_width, m_height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
  // GL's first row is the bottom one; image files start at the top.
  std::vector<std::uint8_t> flipped(pixels.size());
  for (int y = 0; y < m_height; ++y) {
    std::memcpy(flipped.data() + std::size_t(y) * row,
                pixels.data() + std::size_t(m_height - 1 - y) * row, row);
  }
  return flipped;
}

}  // namespace sandphys::render
