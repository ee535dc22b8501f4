#pragma once

// The renderer's GLSL (shaders/render/), embedded at build time by sandphys_embed_shaders(...
// FUNCTION renderShaders) in samples/render/CMakeLists.txt, for sandphys's shader loader.

#include <span>

#include "gl/embedded_shaders.h"

namespace sandphys::gl {

std::span<const EmbeddedShader> renderShaders();

}  // namespace sandphys::gl
