#include "core/log.h"

#include <cstdio>
#include <mutex>
#include <string>

namespace sandphys {
namespace {

std::mutex& handlerMutex() {
  static std::mutex mutex;
  return mutex;
}

LogHandler& currentHandler() {
  static LogHandler handler;
  return handler;
}

}  // namespace

void setLogHandler(LogHandler handler) {
  std::lock_guard lock(handlerMutex());
  currentHandler() = std::move(handler);
}

namespace detail {

void log(LogLevel level, std::string_view message) {
  LogHandler handler;
  {
    // A copy, so that a handler may itself call setLogHandler without a deadlock.
    std::lock_guard lock(handlerMutex());
    handler = currentHandler();
  }
  if (handler) {
    handler(level, message);
    return;
  }
  const char* prefix = level == LogLevel::Error ? "error" : "warning";
  std::fprintf(stderr, "sandphys: %s: %.*s\n", prefix, int(message.size()), message.data());
}

}  // namespace detail
}  // namespace sandphys
