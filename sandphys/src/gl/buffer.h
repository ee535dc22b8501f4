#pragma once

#include <GL/glew.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sandphys::gl {

/// An owned GL buffer object of fixed size (immutable storage; growing makes a new one).
class Buffer {
 public:
  Buffer() = default;
  /// Allocates `bytes` (at least 16) of device memory, zero-filled; throws GpuError on failure.
  explicit Buffer(std::size_t bytes, const char* name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  GLuint id() const { return m_id; }
  std::size_t size() const { return m_bytes; }
  void bindBase(GLenum target, GLuint binding) const;
  void upload(std::size_t offset, std::size_t bytes, const void* data);
  /// Sync point: waits for the GPU.
  void download(std::size_t offset, std::size_t bytes, void* data) const;
  /// The first `count` elements of type T. Sync point.
  template <typename T>
  std::vector<T> downloadArray(std::size_t count) const {
    std::vector<T> out(count);
    if (count > 0) download(0, count * sizeof(T), out.data());
    return out;
  }
  void zero();
  /// Zeroes `bytes` from `offset` (both multiples of 4).
  void zero(std::size_t offset, std::size_t bytes);
  /// Copies this buffer's first `bytes` into a new, larger buffer, which replaces it.
  void grow(std::size_t newBytes, std::size_t bytesToKeep);

 private:
  GLuint m_id = 0;
  std::size_t m_bytes = 0;
  const char* m_name = "";
};

}  // namespace sandphys::gl
