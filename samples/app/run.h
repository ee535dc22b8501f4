#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "app/cli.h"
#include "app/progress.h"
#include "scenes/scene.h"

namespace sandphys::samples {

/// Everything a headless run measured; the metrics JSON is written from it.
struct RunSummary {
  std::string scene;               ///< registry name
  std::uint64_t frames = 0;        ///< frames run
  double frameDt = 0.0;            ///< s
  double setupSeconds = 0.0;       ///< wall time of World creation and Scene::build, s
  double wallSeconds = 0.0;        ///< wall time of the frame loop (steps + scene logic), s
  double hookSeconds = 0.0;        ///< wall time in the frame hooks (screenshots), s; not in
                                   ///< wallSeconds
  double granuleSteps = 0.0;       ///< sum over substeps of the granules alive
  double maxOverlap = 0.0;         ///< largest overlap seen in any frame, m
  double droppedSeconds = 0.0;     ///< frame time dropped by the substep cap, s
  WorldStats stats{};              ///< World::readStats at the end
  std::uint32_t granulesLost = 0;  ///< alive granules outside the scene's container at the end
  float timeStep = 0.0f;           ///< s
  float particleDiameter = 0.0f;   ///< m
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
  float youngsModulus = 0.0f;        ///< Pa, as the World had it
  float maxSpeed = 0.0f;             ///< the speed guard, m/s
  std::uint64_t gpuMemoryBytes = 0;  ///< the world's buffers
  std::string gpu;                   ///< GpuContext::description
  bool sceneFinished = false;        ///< Scene::finished at the end
  std::vector<scenes::SceneMetric> sceneMetrics;
  std::vector<scenes::SceneSeries> sceneSeries;  ///< Scene::series at the end
  std::vector<BodyState> bodies;                 ///< World::readBodies at the end (for exports)
  /// The scene's rigid bodies that are not sand (Scene::bodies) at the end, and every
  /// kBodySeriesFrames frames with the simulated time, s.
  std::vector<scenes::SceneBody> sceneBodies;
  struct BodySample {
    double time = 0.0;
    std::vector<scenes::SceneBody> bodies;
  };
  std::vector<BodySample> bodySeries;
  /// Every frame whose report has statistics: simulated time at its end (s), its wall time (ms,
  /// the stats read makes it wait for the GPU), and the granules alive and asleep.
  struct FrameSample {
    double time = 0.0;
    double wallMilliseconds = 0.0;
    std::uint32_t granules = 0;
    std::uint32_t granulesAsleep = 0;
  };
  std::vector<FrameSample> frameSeries;
};

/// Frames between two samples of RunSummary::bodySeries (10 per second at 60 frames per second).
inline constexpr std::uint64_t kBodySeriesFrames = 6;

/// Called by runScene with the world and the number of frames run so far, e.g. to render
/// screenshots or record the run. Its wall time is kept out of the run's simulation timing.
using FrameHook = std::function<void(World& world, std::uint64_t frame)>;

/// The hooks of runScene; any may be empty.
struct RunHooks {
  FrameHook afterBuild;  ///< once, after Scene::build (frame 0)
  FrameHook afterFrame;  ///< after every frame's step and update
  FrameHook atEnd;       ///< once, after the loop
};

/// Runs `scene` in a new World on `gpu` for `frames` frames of `frameDt` s (stopping early when
/// `untilDone` and the scene finishes), showing progress on `progress`. Reads the stats and the
/// bodies once at the end (sync points); never per frame beyond what the World itself does.
RunSummary runScene(const GpuContext& gpu, scenes::Scene& scene, std::uint64_t frames,
                    double frameDt, bool untilDone, ProgressLine& progress,
                    const RunHooks& hooks = {});

/// Runs the scene of `options` headless and writes its metrics, exports and screenshots (rendered
/// offscreen in the same EGL context); returns the exit code. Throws sandphys::Error and
/// std::runtime_error (I/O) on failure.
int runHeadless(RunOptions& options);

}  // namespace sandphys::samples
