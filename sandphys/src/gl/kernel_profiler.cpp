#include "gl/kernel_profiler.h"

#include <string>

#include "core/assert.h"

namespace sandphys::gl {

KernelProfiler::~KernelProfiler() {
  for (auto& p : m_pending) {
    m_pool.push_back(p.beginQuery);
    if (p.endQuery) m_pool.push_back(p.endQuery);
  }
  if (!m_pool.empty()) glDeleteQueries(static_cast<GLsizei>(m_pool.size()), m_pool.data());
}

void KernelProfiler::begin(const char* kernel) {
  if (!m_enabled) return;
  GLuint query = 0;
  if (m_pool.empty()) {
    glGenQueries(1, &query);
  } else {
    query = m_pool.back();
    m_pool.pop_back();
  }
  // Timestamps, not GL_TIME_ELAPSED: Mesa's llvmpipe reports zero elapsed time for compute.
  glQueryCounter(query, GL_TIMESTAMP);
  m_pending.push_back({kernel, query, 0});
}

void KernelProfiler::end() {
  if (!m_enabled) return;
  SANDPHYS_ASSERT(!m_pending.empty() && m_pending.back().endQuery == 0,
                  "KernelProfiler::end without a begin (" + std::to_string(m_pending.size()) +
                      " dispatches timed)");
  GLuint query = 0;
  if (m_pool.empty()) {
    glGenQueries(1, &query);
  } else {
    query = m_pool.back();
    m_pool.pop_back();
  }
  glQueryCounter(query, GL_TIMESTAMP);
  m_pending.back().endQuery = query;
}

void KernelProfiler::collect() {
  for (auto& [name, beginQuery, endQuery] : m_pending) {
    GLuint64 begin = 0;
    GLuint64 end = 0;
    glGetQueryObjectui64v(beginQuery, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(endQuery, GL_QUERY_RESULT, &end);
    const GLuint64 nanoseconds = end > begin ? end - begin : 0;
    Total* total = nullptr;
    for (auto& t : m_totals) {
      if (t.name == name) total = &t;
    }
    if (!total) total = &m_totals.emplace_back(Total{name, 0.0, 0});
    total->milliseconds += double(nanoseconds) * 1e-6;
    ++total->dispatches;
    m_pool.push_back(beginQuery);
    m_pool.push_back(endQuery);
  }
  m_pending.clear();
}

}  // namespace sandphys::gl
