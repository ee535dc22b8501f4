#pragma once

#include <filesystem>

namespace sandphys::viewer {

/// Writes what has been drawn so far into the window's back buffer (width × height pixels from
/// the bottom left) to a PNG at `path`, creating its directory. Sync point: waits for the GPU.
/// Throws sandphys::Error naming the path when it cannot be written.
void writeBackBufferPng(const std::filesystem::path& path, int width, int height);

}  // namespace sandphys::viewer
