#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace sandphys::samples {

/// A one-line progress display on stderr, rewritten in place with '\r'. Silent for the first few
/// seconds (short runs print nothing) and then updated at most twice per second. When the stream
/// is not a terminal (CI logs, redirected output), whole lines every ten seconds instead.
class ProgressLine {
 public:
  /// `enabled` false makes every call a no-op.
  explicit ProgressLine(bool enabled, std::FILE* stream = stderr);
  /// Ends the line if anything was printed.
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Whether a new line is due (cheap; call it every frame and build the text only when true).
  bool due() const;
  /// Replaces the line with `text`.
  void show(const std::string& text);
  /// Moves to a fresh line, so that later output does not overwrite the progress.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool m_enabled;
  bool m_terminal;
  std::FILE* m_stream;
  Clock::time_point m_start;
  Clock::time_point m_last;
  std::size_t m_lastLength = 0;
  bool m_printed = false;
};

}  // namespace sandphys::samples
