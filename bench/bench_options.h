#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "measure.h"

namespace sandphys::bench {

/// Exit codes of sandphys-bench.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;  ///< a sandphys::Error (GPU, capacity, ...)
inline constexpr int kExitUsage = 2;  ///< a bad command line

/// The whole command line, validated.
struct BenchOptions {
  std::vector<SizePlan> sizes;
  MeasureOptions measure{};
  /// Write the results here as JSON; empty = no file.
  std::string jsonPath;
};

/// Parses the command line into `options`. Returns an exit code when the program should stop now
/// (--help, or a usage error already printed to stderr), nothing when it should run.
std::optional<int> parseCommandLine(int argc, char** argv, BenchOptions& options);

}  // namespace sandphys::bench
