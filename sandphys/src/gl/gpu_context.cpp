#include "sandphys/gpu_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glew.h>

#include <cstring>
#include <string>

#include "sandphys/error.h"

namespace sandphys {

struct GpuContext::Impl {
  bool headless = false;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  ~Impl() {
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
      eglDestroyContext(display, context);
    }
    // The display is shared by every context of the process (EGL keeps one per platform), so it
    // is not terminated here: another GpuContext may still use it.
  }
};

namespace {

std::string eglErrorName(EGLint code) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(code));
  return std::string("EGL error ") + hex;
}

// Loads GL entry points for the current context and checks for OpenGL 4.5 and compute shaders.
void loadAndCheckGl(bool egl) {
  glewExperimental = GL_TRUE;
  GLenum status = glewInit();
  // GLEW 2.2 built for GLX returns GLEW_ERROR_NO_GLX_DISPLAY under an EGL context although it
  // loaded every GL entry point: that code is success for us.
  if (status != GLEW_OK && !(egl && status == GLEW_ERROR_NO_GLX_DISPLAY)) {
    throw GpuError(std::string("glewInit failed: ") +
                   reinterpret_cast<const char*>(glewGetErrorString(status)));
  }
  while (glGetError() != GL_NO_ERROR) {
  }
  GLint major = 0;
  GLint minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (major * 10 + minor < 45) {
    throw GpuError("OpenGL 4.5 core is required, the context offers " + std::to_string(major) +
                   "." + std::to_string(minor) + " (" + (version ? version : "no GL_VERSION") +
                   ")");
  }
  if (!glDispatchCompute || !glMemoryBarrier) {
    throw GpuError("compute shaders are required but glDispatchCompute is missing");
  }
}

}  // namespace

GpuContext::GpuContext(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
GpuContext::GpuContext(GpuContext&&) noexcept = default;
GpuContext& GpuContext::operator=(GpuContext&&) noexcept = default;
GpuContext::~GpuContext() = default;

GpuContext GpuContext::headless() {
  auto impl = std::make_unique<Impl>();
  impl->headless = true;
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!getPlatformDisplay || !clientExtensions ||
      !std::strstr(clientExtensions, "EGL_MESA_platform_surfaceless")) {
    throw GpuError(
        "headless GPU context: EGL has no surfaceless platform (EGL_MESA_platform_surfaceless); "
        "install Mesa's EGL (Debian package libegl-mesa0)");
  }
  impl->display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0;
  EGLint minor = 0;
  if (impl->display == EGL_NO_DISPLAY || !eglInitialize(impl->display, &major, &minor)) {
    throw GpuError("headless GPU context: eglInitialize failed on the surfaceless platform (" +
                   eglErrorName(eglGetError()) + ")");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    throw GpuError("headless GPU context: EGL cannot bind the desktop OpenGL API (" +
                   eglErrorName(eglGetError()) + ")");
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  impl->context = eglCreateContext(impl->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (impl->context == EGL_NO_CONTEXT) {
    throw GpuError("headless GPU context: no OpenGL 4.5 core context available (" +
                   eglErrorName(eglGetError()) + "); sandphys needs OpenGL 4.5 compute shaders");
  }
  if (!eglMakeCurrent(impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl->context)) {
    throw GpuError("headless GPU context: eglMakeCurrent failed (" + eglErrorName(eglGetError()) +
                   ")");
  }
  loadAndCheckGl(true);
  return GpuContext(std::move(impl));
}

GpuContext GpuContext::fromCurrentContext() {
  auto impl = std::make_unique<Impl>();
  // The current context may be EGL (no GLX display): glewInit then reports NO_GLX_DISPLAY.
  loadAndCheckGl(eglGetCurrentContext() != EGL_NO_CONTEXT);
  return GpuContext(std::move(impl));
}

void GpuContext::makeCurrent() const {
  if (m_impl->headless && eglGetCurrentContext() != m_impl->context) {
    eglMakeCurrent(m_impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_impl->context);
  }
}

std::string GpuContext::description() const {
  makeCurrent();
  auto text = [](GLenum name) {
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return text(GL_RENDERER) + " / " + text(GL_VERSION);
}

bool GpuContext::isHeadless() const {
  return m_impl->headless;
}

}  // namespace sandphys
