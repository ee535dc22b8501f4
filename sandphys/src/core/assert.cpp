#include "core/assert.h"

#include <cstdlib>
#include <mutex>
#include <string>

#include "core/log.h"

namespace sandphys {
namespace {

std::mutex& handlerMutex() {
  static std::mutex mutex;
  return mutex;
}

AssertHandler& currentHandler() {
  static AssertHandler handler;
  return handler;
}

}  // namespace

void setAssertHandler(AssertHandler handler) {
  std::lock_guard lock(handlerMutex());
  currentHandler() = std::move(handler);
}

namespace detail {

void assertFailed(std::string_view file, int line, std::string_view condition,
                  std::string_view message) {
  AssertHandler handler;
  {
    // A copy, so that a handler may itself call setAssertHandler without a deadlock.
    std::lock_guard lock(handlerMutex());
    handler = currentHandler();
  }
  const AssertFailure failure{file, line, condition, message};
  if (handler) {
    handler(failure);
  } else {
    std::string text(file);
    text += ':';
    text += std::to_string(line);
    text += ": ";
    text += condition;
    text += ": ";
    text += message;
    log(LogLevel::Error, text);
  }
  std::abort();
}

}  // namespace detail
}  // namespace sandphys
