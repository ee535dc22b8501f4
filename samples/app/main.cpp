// sandphys-samples: the samples app. This build runs scenes headless (metrics, exports); the
// windowed viewer joins it with SANDPHYS_VIEWER.
#include <exception>
#include <iostream>

#include "app/cli.h"
#include "app/run.h"

int main(int argc, char** argv) {
  using namespace sandphys::samples;
  RunOptions options;
  if (std::optional<int> exitCode = parseCommandLine(argc, argv, options)) return *exitCode;
  try {
    return runHeadless(options);
  } catch (const std::exception& error) {
    std::cerr << "sandphys-samples: " << error.what() << '\n';
    return kExitFailure;
  }
}
