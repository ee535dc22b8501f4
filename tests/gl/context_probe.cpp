// Run by CTest with Mesa told to offer an older OpenGL (MESA_GL_VERSION_OVERRIDE): creating a
// headless context and adopting a current 3.3 context must both fail with a message that names
// OpenGL 4.5. Exit status 0 only if both did.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <sandphys/sandphys.h>

#include <cstdio>
#include <string>

namespace {

bool refused(const char* what, void (*attempt)()) {
  try {
    attempt();
  } catch (const sandphys::GpuError& e) {
    std::string message = e.what();
    std::printf("%s: %s\n", what, message.c_str());
    return message.find("OpenGL 4.5") != std::string::npos;
  }
  std::printf("%s: accepted\n", what);
  return false;
}

void adoptOldContext() {
  auto getDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display = getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  eglInitialize(display, nullptr, nullptr);
  eglBindAPI(EGL_OPENGL_API);
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    throw sandphys::GpuError(
        "probe: could not even make a 3.3 context current (not an OpenGL 4.5 check)");
  }
  sandphys::GpuContext adopted = sandphys::GpuContext::fromCurrentContext();
}

}  // namespace

int main() {
  bool headless = refused("headless", [] { sandphys::GpuContext::headless(); });
  bool adopted = refused("adopted 3.3 context", adoptOldContext);
  return headless && adopted ? 0 : 1;
}
