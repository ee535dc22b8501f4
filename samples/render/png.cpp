#include "render/png.h"

#include <stb/stb_image_write.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include <sandphys/error.h>

namespace sandphys::render {

void writePng(const std::filesystem::path& path, int width, int height,
              std::span<const std::uint8_t> rgba) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4) {
    throw InvalidArgument("writePng '" + path.string() + "': " + std::to_string(rgba.size()) +
                          " bytes do not hold a " + std::to_string(width) + "x" +
                          std::to_string(height) + " RGBA image");
  }
  std::vector<std::uint8_t> rgb(std::size_t(width) * std::size_t(height) * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    std::memcpy(&rgb[3 * i], &rgba[4 * i], 3);
  }
  errno = 0;
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) {
    const std::string reason = errno ? std::strerror(errno) : "write failed";
    throw Error("cannot write PNG '" + path.string() + "': " + reason);
  }
}

}  // namespace sandphys::render
