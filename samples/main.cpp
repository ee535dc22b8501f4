// sandphys-samples: the samples app. Runs a scene headless (metrics, exports, offscreen
// screenshots) or, in a build with SANDPHYS_VIEWER and without --headless, in the viewer's window.
#include <exception>
#include <iostream>

#include "app/cli.h"
#include "app/golden.h"
#include "app/recording.h"
#include "app/replay.h"
#include "app/run.h"
#ifdef SANDPHYS_HAS_VIEWER
#include "viewer/viewer.h"
#endif

int main(int argc, char** argv) {
  using namespace sandphys::samples;
  RunOptions options;
  if (std::optional<int> exitCode = parseCommandLine(argc, argv, options)) return *exitCode;
  try {
    if (!options.replayPath.empty()) return runReplay(options.replayPath, options.quiet);
    if (!options.goldenDir.empty()) return writeGoldens(options.goldenDir, options.quiet);
#ifdef SANDPHYS_HAS_VIEWER
    if (!options.headless) return runViewer(options);
#else
    if (!options.playPath.empty()) {
      std::cerr << "sandphys-samples: --play " << options.playPath.string()
                << ": this build has no viewer (configure with SANDPHYS_VIEWER=ON); --replay "
                   "checks a recording headless\n";
      return kExitUsage;
    }
    if (!options.headless) {
      std::cerr << "sandphys-samples: no --headless given, but this build has no viewer "
                   "(configure with SANDPHYS_VIEWER=ON); running headless\n";
    }
#endif
    return runHeadless(options);
  } catch (const std::exception& error) {
    std::cerr << "sandphys-samples: " << error.what() << '\n';
    return kExitFailure;
  }
}
