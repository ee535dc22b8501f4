// sandphys-bench-playback: what the viewer's --play costs on a recording, headless: building its
// scene, playing every frame with its check, showing snapshots behind and ahead, putting the
// re-simulated state back, and going on from a snapshot behind (a rebuild and a re-simulation).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <vector>

#include <sandphys/sandphys.h>
#include <CLI/CLI.hpp>

#include "app/playback.h"

namespace {

using Clock = std::chrono::steady_clock;
using sandphys::samples::Playback;

constexpr double kNoBudget = std::numeric_limits<double>::infinity();

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Scrubs to every recorded snapshot in `frames` and returns the slowest, ms; `shown` counts those
// shown at once.
double scrubTo(Playback& playback, const std::vector<std::uint64_t>& frames, int& shown) {
  double slowest = 0.0;
  shown = 0;
  for (const std::uint64_t frame : frames) {
    const Clock::time_point start = Clock::now();
    playback.scrubTo(frame);
    slowest = std::max(slowest, millisecondsSince(start));
    if (playback.showingSnapshot() && playback.shownFrame() == frame) ++shown;
  }
  return slowest;
}

int run(const std::string& file) {
  const sandphys::GpuContext gpu = sandphys::GpuContext::headless();
  sandphys::Recording recording = sandphys::readRecording(file);
  const double recordedSeconds = recording.wallSeconds;
  std::vector<std::uint64_t> snapshots;
  for (const sandphys::WorldSnapshot& snapshot : recording.snapshots) {
    if (snapshot.frame > 0) snapshots.push_back(snapshot.frame);
  }
  std::printf("recording %s: %zu frames, %zu snapshots, recorded run %.2f s; %s\n", file.c_str(),
              recording.frames.size(), recording.snapshots.size(), recordedSeconds,
              gpu.description().c_str());

  Clock::time_point start = Clock::now();
  Playback playback(gpu, std::move(recording));
  std::printf("build the scene and its World      %10.1f ms\n", millisecondsSince(start));
  const std::uint64_t frames = playback.frames();

  int shown = 0;
  double slowest = scrubTo(playback, snapshots, shown);
  std::printf("scrub ahead to each snapshot        %10.2f ms at most (%d of %zu shown at once)\n",
              slowest, shown, snapshots.size());
  playback.scrubTo(0);

  start = Clock::now();
  while (playback.shownFrame() < frames) {
    playback.playOn(1);
    playback.advance(kNoBudget);
  }
  const double played = millisecondsSince(start) * 1e-3;
  std::printf("play every frame, each checked      %10.2f s (%.1f ms a frame, %.2fx the run)\n",
              played, played * 1e3 / static_cast<double>(frames),
              recordedSeconds > 0.0 ? played / recordedSeconds : 0.0);

  std::vector<std::uint64_t> behind;
  for (auto frame = snapshots.rbegin(); frame != snapshots.rend(); ++frame) {
    if (*frame < frames) behind.push_back(*frame);
  }
  slowest = scrubTo(playback, behind, shown);
  std::printf("scrub back to each snapshot         %10.2f ms at most (%d of %zu shown at once)\n",
              slowest, shown, behind.size());
  start = Clock::now();
  playback.scrubTo(frames);
  std::printf("back to the last frame's own state  %10.2f ms\n", millisecondsSince(start));

  const std::uint64_t middle = snapshots.empty() ? 0 : snapshots[(snapshots.size() - 1) / 2];
  playback.scrubTo(middle);
  start = Clock::now();
  playback.playOn(1);
  playback.advance(kNoBudget);
  std::printf("go on from the snapshot of frame %-4llu %9.2f s (a rebuild and %llu frames)\n",
              static_cast<unsigned long long>(middle), millisecondsSince(start) * 1e-3,
              static_cast<unsigned long long>(playback.shownFrame()));

  if (const auto& mismatch = playback.mismatch()) {
    std::printf("differs from the recording at %s\n", mismatch->what.c_str());
    return 1;
  }
  std::printf("every frame re-simulated as recorded (%llu)\n",
              static_cast<unsigned long long>(playback.checkedFrames()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "sandphys-bench-playback: what the viewer's --play costs on a recording (made with "
      "sandphys-samples --record), headless"};
  std::string file;
  app.add_option("recording", file, "the recording FILE")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(file);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sandphys-bench-playback: %s\n", error.what());
    return 1;
  }
}
