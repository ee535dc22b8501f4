// sandphys-bench: Cundall number vs granule count on the settled cylinder pile of the paper or the
// standard box pile (--scene), with per-kernel GPU times. See --help, and report.h for the output.
#include <cstdio>
#include <exception>
#include <thread>

#include <sandphys/sandphys.h>

#include "bench_options.h"
#include "measure.h"
#include "report.h"

int main(int argc, char** argv) {
  using namespace sandphys::bench;
  BenchOptions options;
  if (const auto exitCode = parseCommandLine(argc, argv, options)) return *exitCode;
  try {
    const sandphys::GpuContext gpu = sandphys::GpuContext::headless();
    BenchReport report;
    report.gpu = gpu.description();
    report.hardwareThreads = std::thread::hardware_concurrency();
    if (options.measure.progress) std::fprintf(stderr, "GPU: %s\n", report.gpu.c_str());
    for (const SizePlan& plan : options.sizes) {
      report.sizes.push_back(measureSize(gpu, plan, options.measure));
      // Results so far survive a later size that fails or is interrupted.
      if (!options.jsonPath.empty()) writeJson(options.jsonPath, reportJson(options, report));
    }
    printReport(stdout, options, report);
  } catch (const sandphys::Error& error) {
    std::fprintf(stderr, "sandphys-bench: %s\n", error.what());
    return kExitError;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sandphys-bench: unexpected error: %s\n", error.what());
    return kExitError;
  }
  return kExitOk;
}
