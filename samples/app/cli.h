#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/render_quality.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Exit code of a run that finished.
inline constexpr int kExitOk = 0;
/// Exit code when the simulation or writing its output failed.
inline constexpr int kExitFailure = 1;
/// Exit code of a usage error (unknown flag, bad value, unknown scene, unwritable path).
inline constexpr int kExitUsage = 2;

/// Largest --frame-budget accepted, ms (ten seconds a frame is no longer a viewer).
inline constexpr double kMaxFrameBudgetMs = 10000.0;

/// Width and height of an image or a window, px.
struct ImageSize {
  int width = 1280;  ///< px, in 1..8192
  int height = 720;  ///< px, in 1..8192
};

/// What the command line asked for, validated.
struct RunOptions {
  /// Registry name of the scene.
  std::string sceneName = "cylinder-pile";
  /// The scene, made from the registry with the command line's parameters applied.
  std::unique_ptr<scenes::Scene> scene;
  /// --headless was given: no window even in a build with the viewer (SANDPHYS_VIEWER).
  bool headless = false;
  /// Frames to run (the cap with --until-done); >= 0.
  std::uint64_t frames = 300;
  /// --frames was given explicitly: a windowed run quits after `frames` frames only then.
  bool framesGiven = false;
  /// Duration of one frame, s; > 0.
  double frameDt = 1.0 / 60.0;
  /// Stop as soon as the scene reports it is finished.
  bool untilDone = false;
  /// No progress line.
  bool quiet = false;
  /// Where to write the metrics JSON; empty for none.
  std::filesystem::path metricsPath;
  /// Where to export the granules at the end (.csv or .vtk each).
  std::vector<std::filesystem::path> exportPaths;
  /// Folder to write a LAMMPS deck of the last frame's World to (--export-lammps); empty for none.
  std::filesystem::path lammpsDir;
  /// PNG of the last frame (--screenshot); empty for none. Checked writable, ends in .png.
  std::filesystem::path screenshotPath;
  /// Size of screenshots and of the viewer's window (--size WxH).
  ImageSize size;
  /// Folder of an image sequence frame_NNNNNN.png (--screenshots); empty for none. Exists and is
  /// writable once parsed.
  std::filesystem::path screenshotDir;
  /// Frames between two images of the sequence (--every); >= 1.
  std::uint64_t every = 10;
  /// Wall-clock time one viewer frame may take, ms, in [0, kMaxFrameBudgetMs] (--frame-budget).
  /// The viewer runs as many substeps as fit (slow motion when that is less than a frame dt);
  /// 0 = off: every frame simulates its whole frame dt, however long that takes. Window only.
  double frameBudgetMs = 50.0;
  /// Render quality preset (--quality); empty = auto: the viewer picks it from its measured
  /// render times, a headless run draws high.
  std::optional<render::RenderQuality> quality;
  /// Where to record the run (--record); empty for none. Checked writable.
  std::filesystem::path recordPath;
  /// Frames between two full snapshots of a recording (--snapshot-every); >= 1.
  std::uint64_t snapshotEvery = 60;
  /// A recording to replay headless and check frame by frame (--replay); the scene and its
  /// settings come from it, and `scene` stays empty.
  std::filesystem::path replayPath;
  /// A recording to show in the viewer's window on a timeline (--play); the scene and its settings
  /// come from it, and `scene` stays empty.
  std::filesystem::path playPath;
  /// Folder to write every scene's golden metrics to (--write-goldens); empty for none.
  std::filesystem::path goldenDir;
  /// A windowed run's screenshots show the whole window, panel included, instead of the scene
  /// alone (--panel-in-screenshots).
  bool panelInScreenshots = false;
};

/// Parses and validates the command line, and makes the scene. Returns the options to run, or an
/// exit code when the program should stop: after --help or --list (kExitOk), or after printing a
/// usage error that names the flag and the value to stderr (kExitUsage). Touches no GPU; may
/// create the --screenshots folder.
std::optional<int> parseCommandLine(int argc, char** argv, RunOptions& options);

}  // namespace sandphys::samples
