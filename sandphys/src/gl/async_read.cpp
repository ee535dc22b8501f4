#include "gl/async_read.h"

namespace sandphys::gl {

AsyncRead::~AsyncRead() {
  if (m_fence) glDeleteSync(m_fence);
}

void AsyncRead::start(const Buffer& source, std::size_t offset, std::size_t bytes) {
  if (m_fence) glDeleteSync(m_fence);
  if (m_copy.size() < bytes) m_copy = Buffer(bytes, m_name);
  m_bytes = bytes;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glCopyNamedBufferSubData(source.id(), m_copy.id(), static_cast<GLintptr>(offset), 0,
                           static_cast<GLsizeiptr>(m_bytes));
  m_fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

bool AsyncRead::take(void* out) {
  if (!m_fence) return false;
  // Flushed, so that the fence is reached without the CPU asking again.
  const GLenum state = glClientWaitSync(m_fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  if (state == GL_TIMEOUT_EXPIRED || state == GL_WAIT_FAILED) return false;
  glDeleteSync(m_fence);
  m_fence = nullptr;
  glGetNamedBufferSubData(m_copy.id(), 0, static_cast<GLsizeiptr>(m_bytes), out);
  return true;
}

}  // namespace sandphys::gl
