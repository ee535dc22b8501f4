#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <initializer_list>
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

/// The exit code of a usage error (samples/app/cli.h, kExitUsage).
inline constexpr int kUsageExit = 2;

/// Runs `command` and expects a usage error whose output names each of `named` (flags, values);
/// `arguments` is what the failure messages quote.
inline void expectUsageErrorOf(const std::string& command, const std::string& arguments,
                               std::initializer_list<const char*> named) {
  const ProcessResult result = runCommand(command);
  EXPECT_EQ(result.exitCode, kUsageExit) << arguments << "\n" << result.output;
  for (const char* text : named) {
    EXPECT_NE(result.output.find(text), std::string::npos)
        << "'" << text << "' not named for: " << arguments << "\n"
        << result.output;
  }
}

}  // namespace sandphys::testing
