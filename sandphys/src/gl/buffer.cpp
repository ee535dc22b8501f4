#include "gl/buffer.h"

#include <algorithm>
#include <string>
#include <utility>

#include "gl/gl_check.h"
#include "sandphys/error.h"

namespace sandphys::gl {

Buffer::Buffer(std::size_t bytes, const char* name)
    : m_bytes(std::max<std::size_t>(bytes, 16)), m_name(name) {
  glCreateBuffers(1, &m_id);
  glNamedBufferStorage(m_id, static_cast<GLsizeiptr>(m_bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    throw GpuError("cannot allocate GPU buffer '" + std::string(name) + "' of " +
                   std::to_string(m_bytes) + " bytes: " + errorName(err));
  }
  zero();
}

Buffer::~Buffer() {
  if (m_id) glDeleteBuffers(1, &m_id);
}

Buffer::Buffer(Buffer&& other) noexcept
    : m_id(std::exchange(other.m_id, 0)),
      m_bytes(std::exchange(other.m_bytes, 0)),
      m_name(other.m_name) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    if (m_id) glDeleteBuffers(1, &m_id);
    m_id = std::exchange(other.m_id, 0);
    m_bytes = std::exchange(other.m_bytes, 0);
    m_name = other.m_name;
  }
  return *this;
}

void Buffer::bindBase(GLenum target, GLuint binding) const {
  glBindBufferBase(target, binding, m_id);
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
  if (bytes == 0) return;
  glNamedBufferSubData(m_id, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::download(std::size_t offset, std::size_t bytes, void* data) const {
  if (bytes == 0) return;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(m_id, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                          data);
}

void Buffer::zero() {
  glClearNamedBufferData(m_id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void Buffer::zero(std::size_t offset, std::size_t bytes) {
  glClearNamedBufferSubData(m_id, GL_R32UI, static_cast<GLintptr>(offset),
                            static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT,
                            nullptr);
}

void Buffer::grow(std::size_t newBytes, std::size_t bytesToKeep) {
  if (newBytes <= m_bytes) return;
  Buffer bigger(newBytes, m_name);
  glCopyNamedBufferSubData(m_id, bigger.m_id, 0, 0,
                           static_cast<GLsizeiptr>(std::min(bytesToKeep, m_bytes)));
  *this = std::move(bigger);
}

}  // namespace sandphys::gl
