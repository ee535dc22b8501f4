#pragma once

#include "app/cli.h"

namespace sandphys::samples {

/// Runs the samples app with a window: the scene of `options` in a GLFW window with an OpenGL 4.5
/// core context shared with the library, a Dear ImGui panel, mouse camera and sand tools.
/// Honours `--frames N` when given explicitly (quits after N frames) and `--screenshot FILE`
/// (written from the last frame before quitting). Returns the process exit code; throws
/// sandphys::Error and std::runtime_error when the window, the context or the simulation fail.
int runViewer(RunOptions& options);

}  // namespace sandphys::samples
