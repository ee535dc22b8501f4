#pragma once

#include <string_view>

#include "sandphys/assert.h"

/// Checks an internal invariant of the library (never a user's input: that throws
/// sandphys::Error). `message` is evaluated only when `condition` is false, so it may format the
/// values involved.
#define SANDPHYS_ASSERT(condition, message)                                                      \
  do {                                                                                           \
    if (!(condition)) ::sandphys::detail::assertFailed(__FILE__, __LINE__, #condition, message); \
  } while (false)

namespace sandphys::detail {

/// Hands the failure to the handler of setAssertHandler (a log line by default), then aborts.
[[noreturn]] void assertFailed(std::string_view file, int line, std::string_view condition,
                               std::string_view message);

}  // namespace sandphys::detail
