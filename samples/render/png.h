#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace sandphys::render {

/// Writes an RGBA image (4 bytes per pixel, rows from the top) as an RGB PNG file: the alpha
/// channel is dropped, a rendered frame is opaque. Throws sandphys::Error naming the path when
/// the file cannot be written, InvalidArgument when the size does not match the pixels.
void writePng(const std::filesystem::path& path, int width, int height,
              std::span<const std::uint8_t> rgba);

}  // namespace sandphys::render
