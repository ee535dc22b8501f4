#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_options.h"
#include "measure.h"

namespace sandphys::bench {

/// What the whole run measured, for the table and the JSON.
struct BenchReport {
  std::string gpu;               ///< GpuContext::description()
  unsigned hardwareThreads = 0;  ///< std::thread::hardware_concurrency()
  std::vector<SizeResult> sizes;
};

/// The tables (performance, settling, per-kernel times) and notes, for people.
void printReport(std::FILE* out, const BenchOptions& options, const BenchReport& report);

/// Everything, for scripts: options, machine, and per size every number of the tables.
nlohmann::json reportJson(const BenchOptions& options, const BenchReport& report);

/// Writes `json` to `path` (indented); throws sandphys::Error naming the path on failure.
void writeJson(const std::string& path, const nlohmann::json& json);

}  // namespace sandphys::bench
