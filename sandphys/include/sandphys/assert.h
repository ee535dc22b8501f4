#pragma once

#include <functional>
#include <string_view>

namespace sandphys {

/// An internal invariant of sandphys that did not hold: a bug in sandphys (or its memory
/// overwritten from outside), never a misuse of the API, which throws sandphys::Error instead.
struct AssertFailure {
  std::string_view file;       ///< source file of the check, as the compiler named it
  int line = 0;                ///< line of the check
  std::string_view condition;  ///< the expression that was false
  std::string_view message;    ///< what it means, with the values involved
};

/// Called with every failed internal check, on the thread that made it. The views live until
/// the handler returns.
using AssertHandler = std::function<void(const AssertFailure& failure)>;

/// Sends every failed internal check of this process to `handler` from now on (a game's crash
/// reporter, a test); an empty handler restores the default, which logs "file:line: condition:
/// message" as LogLevel::Error (setLogHandler). Whatever the handler, sandphys aborts the process
/// once it returns: the state it checked is broken, so going on would only hide the bug. A
/// handler that must not end the process throws instead (its exception leaves the sandphys call
/// that failed; an exception through a noexcept call terminates). Process-wide, like
/// setLogHandler; safe to call from any thread. The checks cost a comparison on the CPU, never
/// one per particle, and are on in every build.
void setAssertHandler(AssertHandler handler);

}  // namespace sandphys
