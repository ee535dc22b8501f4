#include "viewer/screenshot.h"

#include <GL/glew.h>

#include <cstdint>
#include <cstring>
#include <system_error>
#include <vector>

#include "render/png.h"

namespace sandphys::viewer {

void writeBackBufferPng(const std::filesystem::path& path, int width, int height) {
  if (width <= 0 || height <= 0) return;  // a minimised window has nothing to show
  const std::size_t rowBytes = static_cast<std::size_t>(width) * 4;
  std::vector<std::uint8_t> pixels(rowBytes * static_cast<std::size_t>(height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  // GL counts rows from the bottom, image files from the top.
  std::vector<std::uint8_t> row(rowBytes);
  for (int y = 0; y < height / 2; ++y) {
    std::uint8_t* top = pixels.data() + static_cast<std::size_t>(y) * rowBytes;
    std::uint8_t* bottom = pixels.data() + static_cast<std::size_t>(height - 1 - y) * rowBytes;
    std::memcpy(row.data(), top, rowBytes);
    std::memcpy(top, bottom, rowBytes);
    std::memcpy(bottom, row.data(), rowBytes);
  }
  if (path.has_parent_path()) {
    std::error_code ignored;  // writePng names the path if the directory is still missing
    std::filesystem::create_directories(path.parent_path(), ignored);
  }
  render::writePng(path, width, height, pixels);
}

}  // namespace sandphys::viewer
