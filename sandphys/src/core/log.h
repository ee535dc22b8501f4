#pragma once

#include <string_view>

#include "sandphys/log.h"

namespace sandphys::detail {

/// Hands `message` to the handler of setLogHandler (stderr by default).
void log(LogLevel level, std::string_view message);

}  // namespace sandphys::detail
