#pragma once

#include <GL/glew.h>

#include <string>
#include <vector>

namespace sandphys::gl {

/// GL timer queries around each dispatch, summed per kernel name over one frame. Off unless
/// WorldSettings::profileKernels; reading the results waits for the GPU.
class KernelProfiler {
 public:
  struct Total {
    std::string name;
    double milliseconds = 0.0;
    unsigned dispatches = 0;
  };

  KernelProfiler() = default;
  ~KernelProfiler();
  KernelProfiler(const KernelProfiler&) = delete;
  KernelProfiler& operator=(const KernelProfiler&) = delete;

  void setEnabled(bool enabled) { m_enabled = enabled; }
  bool enabled() const { return m_enabled; }
  /// Starts timing a dispatch of `kernel` (a string literal; compared by address first).
  void begin(const char* kernel);
  void end();
  /// Waits for every pending query and adds the times to the totals; then clears the pending list.
  void collect();
  void resetTotals() { m_totals.clear(); }
  const std::vector<Total>& totals() const { return m_totals; }

 private:
  bool m_enabled = false;
  std::vector<GLuint> m_pool;
  struct Pending {
    const char* name;
    GLuint beginQuery;
    GLuint endQuery;
  };
  std::vector<Pending> m_pending;
  std::vector<Total> m_totals;
};

}  // namespace sandphys::gl
