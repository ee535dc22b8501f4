#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace sandphys::testing {

/// Exit code and combined stdout + stderr of a finished command.
struct ProcessResult {
  int exitCode = -1;
  std::string output;
};

/// Runs `command` through the shell and waits for it.
inline ProcessResult runCommand(const std::string& command) {
  ProcessResult result;
  std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) {
    result.output.append(buffer.data(), n);
  }
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace sandphys::testing
