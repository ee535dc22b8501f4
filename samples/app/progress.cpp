#include "app/progress.h"

#include <unistd.h>

namespace sandphys::samples {

namespace {

// A run shorter than this prints no progress at all; after it, a line every kInterval.
constexpr std::chrono::seconds kQuietStart{3};
constexpr std::chrono::milliseconds kInterval{500};
// In a log every line stays, so fewer of them.
constexpr std::chrono::seconds kLogInterval{10};

}  // namespace

ProgressLine::ProgressLine(bool enabled, std::FILE* stream)
    : m_enabled(enabled),
      m_terminal(isatty(fileno(stream)) != 0),
      m_stream(stream),
      m_start(Clock::now()),
      m_last(m_start) {}

ProgressLine::~ProgressLine() {
  finish();
}

bool ProgressLine::due() const {
  if (!m_enabled) return false;
  const Clock::time_point now = Clock::now();
  if (!m_terminal) return now - m_last >= kLogInterval;
  return now - m_start >= kQuietStart && now - m_last >= kInterval;
}

void ProgressLine::show(const std::string& text) {
  if (!m_enabled) return;
  m_last = Clock::now();
  if (!m_terminal) {
    std::fprintf(m_stream, "%s\n", text.c_str());
    std::fflush(m_stream);
    return;
  }
  // Pad with blanks so that a shorter line fully covers the previous one.
  const int padding = m_lastLength > text.size() ? static_cast<int>(m_lastLength - text.size()) : 0;
  std::fprintf(m_stream, "\r%s%*s", text.c_str(), padding, "");
  std::fflush(m_stream);
  m_lastLength = text.size();
  m_printed = true;
}

void ProgressLine::finish() {
  if (m_printed) {
    std::fputc('\n', m_stream);
    std::fflush(m_stream);
    m_printed = false;
    m_lastLength = 0;
  }
}

}  // namespace sandphys::samples
