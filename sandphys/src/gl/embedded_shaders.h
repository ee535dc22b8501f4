#pragma once

#include <span>

namespace sandphys::gl {

/// One GLSL file from shaders/, embedded at build time (cmake/embed_shaders.cmake).
struct EmbeddedShader {
  const char* name;    ///< path relative to shaders/, e.g. "sim/contacts.comp"
  const char* source;  ///< file contents
};

std::span<const EmbeddedShader> embeddedShaders();

}  // namespace sandphys::gl
