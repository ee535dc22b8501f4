#pragma once

#include <GL/glew.h>

#include <string>

namespace sandphys::gl {

/// Throws GpuError naming `what` and the GL error if glGetError reports one. Used at setup and
/// read-back, never inside the step loop.
void check(const char* what);

/// Human name of a GL error code.
std::string errorName(GLenum code);

}  // namespace sandphys::gl
