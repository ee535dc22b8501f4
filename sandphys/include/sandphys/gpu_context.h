#pragma once

#include <memory>
#include <string>

namespace sandphys {

/// The OpenGL 4.5 context every World runs in. Create one per thread that simulates.
class GpuContext {
 public:
  /// A context with no window: EGL on Mesa's surfaceless platform (any GPU, or llvmpipe on the
  /// CPU). Throws GpuError naming what is missing (EGL, the platform, GL 4.5, compute shaders).
  static GpuContext headless();
  /// Adopts the context the application made current on this thread (GLFW, SDL, ...). It must be
  /// OpenGL >= 4.5 core; the application keeps owning it.
  static GpuContext fromCurrentContext();

  GpuContext(GpuContext&&) noexcept;
  GpuContext& operator=(GpuContext&&) noexcept;
  ~GpuContext();

  /// Makes the context current on the calling thread (a no-op for an adopted context).
  void makeCurrent() const;
  /// GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile)".
  std::string description() const;
  bool isHeadless() const;

 private:
  struct Impl;
  explicit GpuContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sandphys
