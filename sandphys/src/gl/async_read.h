#pragma once

#include <GL/glew.h>

#include <cstddef>

#include "gl/buffer.h"

namespace sandphys::gl {

/// A copy of part of a buffer that the CPU reads once the GPU has made it, never waiting for it:
/// for a hint that a later frame uses if it is ready (one small copy and a fence).
class AsyncRead {
 public:
  /// Its buffer, labelled `name`, is made by the first start (with a GL context current).
  explicit AsyncRead(const char* name) : m_name(name) {}
  ~AsyncRead();
  AsyncRead(const AsyncRead&) = delete;
  AsyncRead& operator=(const AsyncRead&) = delete;

  /// Copies `bytes` of `source` from `offset`, as the shaders before it left them; a copy started
  /// before and not taken is dropped.
  void start(const Buffer& source, std::size_t offset, std::size_t bytes);
  /// Writes the last copy to `out` and returns true if the GPU has made it (once per copy);
  /// returns false at once if it has not, or there is none.
  bool take(void* out);

 private:
  const char* m_name;
  Buffer m_copy;
  std::size_t m_bytes = 0;
  GLsync m_fence = nullptr;
};

}  // namespace sandphys::gl
