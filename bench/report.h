#pragma once

#include <cstdint>
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

/// The pile a run measures, as its JSON states it: "benchmark", "description" and the scene's
/// "options" (container, material, time step, packing, seed); the settled pile's name in
/// --pile-cache is made from it too.
nlohmann::json pileJson(const MeasureOptions& measure);

/// Everything, for scripts: options, machine, and per size every number of the tables.
nlohmann::json reportJson(const BenchOptions& options, const BenchReport& report);

/// A 64-bit hash as the 16 hex digits the JSON and the pile cache's file names use.
std::string hex(std::uint64_t value);

/// Writes `json` to `path` (indented); throws sandphys::Error naming the path on failure.
void writeJson(const std::string& path, const nlohmann::json& json);

}  // namespace sandphys::bench
