#pragma once

#include <functional>
#include <string_view>

namespace sandphys {

/// How much a message from sandphys matters.
enum class LogLevel {
  Warning,  ///< something the caller should know and may want to fix (dropped frame time, an
            ///< open mesh, bodies placed inside each other); the simulation goes on
  Error,    ///< an internal check failed (sandphys/assert.h); the process aborts next
};

/// Where sandphys's messages go: called with the level and the message (no prefix, no newline),
/// on the thread that made the call that produced it.
using LogHandler = std::function<void(LogLevel level, std::string_view message)>;

/// Sends every message of this process to `handler` from now on (a game's console, a test's
/// capture); an empty handler restores the default, which writes "sandphys: warning: " (or
/// "error: ") and the message to stderr. Process-wide, like the GPU driver behind it; safe to call
/// from any thread.
void setLogHandler(LogHandler handler);

}  // namespace sandphys
