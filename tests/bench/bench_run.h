#pragma once

// One run of sandphys-bench (SANDPHYS_BENCH_EXE) for the bench tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "process.h"

namespace sandphys::testing {

/// The bench on the tests' box pile of 256 granules, settled `settleSteps` substeps from its
/// lattice and timed for `steps`, without progress lines; the caller adds the options it tests.
inline std::string smallBoxBench(int settleSteps, int steps) {
  return std::string(SANDPHYS_BENCH_EXE) + " --scene box --sizes 256 --settle-steps " +
         std::to_string(settleSteps) + " --steps " + std::to_string(steps) + " --quiet";
}

/// Runs `command` (the bench and its options), which must exit with 0, with --json `json`, and
/// returns that JSON's first size; the run's output goes to `output` when given.
inline nlohmann::json benchSize(const std::string& command, const std::filesystem::path& json,
                                std::string* output = nullptr) {
  const ProcessResult result = runCommand(command + " --json " + json.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  if (output) *output = result.output;
  std::ifstream file(json);
  return nlohmann::json::parse(file).at("sizes").at(0);
}

}  // namespace sandphys::testing
