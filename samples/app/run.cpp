#include "app/run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "app/export.h"
#include "app/metrics.h"
#include "app/recording.h"
#include "render/offscreen_target.h"
#include "render/png.h"
#include "render/render_quality.h"
#include "render/renderer.h"

namespace sandphys::samples {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string progressText(std::uint64_t frame, std::uint64_t frames, const World& world,
                         const StepReport& report, double cundall, const scenes::Scene& scene) {
  char buffer[256];
  const unsigned granules = report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
  const int length = std::snprintf(
      buffer, sizeof buffer, "frame %llu/%llu  t %.3f s  granules %u  contacts %s  Cundall %.3g",
      static_cast<unsigned long long>(frame), static_cast<unsigned long long>(frames),
      world.simulatedTime(), granules,
      report.hasStats ? std::to_string(report.stats.contacts).c_str() : "-", cundall);
  std::string text(buffer, static_cast<std::size_t>(std::max(length, 0)));
  const std::string status = scene.status();
  if (!status.empty()) text += "  " + status;
  return text;
}

// Headless screenshots: one renderer and one offscreen target for the whole run.
class Screenshots {
 public:
  Screenshots(const scenes::Scene& scene, ImageSize size, render::RenderQuality quality)
      : m_scene(scene), m_size(size), m_target(size.width, size.height) {
    render::applyRenderQuality(quality, m_renderer.settings());
  }

  void write(World& world, const std::filesystem::path& path) {
    // The scene's own view of what it holds now: one read-back per image (a sync point, as
    // writing a file is anyway).
    const render::Camera camera =
        render::Camera::framing(m_scene.view(scenes::contentsOf(m_scene, world)),
                                float(m_size.width) / float(m_size.height));
    m_target.bind();
    m_renderer.draw(world, camera, m_scene.bounds(), m_size.width, m_size.height,
                    m_scene.surfaces());
    const std::vector<std::uint8_t> pixels = m_target.readRgba();
    const render::RenderStats& stats = m_renderer.finishStats();
    m_gpuMilliseconds += stats.totalMs;
    ++m_images;
    render::writePng(path, m_size.width, m_size.height, pixels);
  }

  std::uint64_t images() const { return m_images; }
  double gpuMillisecondsPerImage() const { return m_images ? m_gpuMilliseconds / m_images : 0.0; }

 private:
  const scenes::Scene& m_scene;
  ImageSize m_size;
  render::OffscreenTarget m_target;
  render::Renderer m_renderer;
  double m_gpuMilliseconds = 0.0;
  std::uint64_t m_images = 0;
};

// The scene's own script runs in sandphys only: the deck says so, with where the scene stood.
LammpsExportOptions lammpsOptions(const scenes::Scene& scene) {
  const std::string status = scene.status();
  return {.notes = {"the " + std::string(scene.name()) + " scene's script" +
                    (status.empty() ? std::string() : " (it stood at \"" + status + "\")") +
                    ": what it does next in sandphys (drops, gates, pours, pushes) is not in this "
                    "deck"}};
}

std::filesystem::path sequencePath(const std::filesystem::path& directory, std::uint64_t frame) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(frame));
  return directory / name;
}

}  // namespace

RunSummary runScene(const GpuContext& gpu, scenes::Scene& scene, std::uint64_t frames,
                    double frameDt, bool untilDone, ProgressLine& progress, const RunHooks& hooks) {
  RunSummary summary;
  summary.scene = std::string(scene.name());
  summary.frameDt = frameDt;
  summary.gpu = gpu.description();

  const Clock::time_point setupStart = Clock::now();
  World world(gpu, scene.settings());
  scene.build(world);
  summary.setupSeconds = secondsSince(setupStart);
  summary.timeStep = world.timeStep();
  summary.particleDiameter = world.settings().particleDiameter;
  summary.contactLaw = world.settings().contactLaw;
  summary.youngsModulus = world.settings().material.youngsModulus;
  summary.maxSpeed = world.settings().maxSpeed;
  if (hooks.afterBuild) {
    const Clock::time_point hookStart = Clock::now();
    hooks.afterBuild(world, 0);
    summary.hookSeconds += secondsSince(hookStart);
  }

  const Clock::time_point loopStart = Clock::now();
  for (std::uint64_t frame = 0; frame < frames; ++frame) {
    if (untilDone && scene.finished()) break;
    const Clock::time_point frameStart = Clock::now();
    const StepReport report = scene.step(world, static_cast<float>(frameDt));
    if (report.hasStats) {
      summary.frameSeries.push_back({world.simulatedTime(), 1e3 * secondsSince(frameStart),
                                     report.stats.granulesAlive, report.stats.granulesAsleep});
    }
    // Count the granules this step moved before the scene may add the next batch.
    const std::uint32_t granules =
        report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
    summary.granuleSteps += static_cast<double>(granules) * report.substeps;
    summary.droppedSeconds += report.droppedTime;
    // The world resets its maximum overlap at every stats read, so the run's maximum is ours.
    if (report.hasStats) summary.maxOverlap = std::max(summary.maxOverlap, report.stats.maxOverlap);
    scene.update(world, report, world.simulatedTime());
    summary.frames = frame + 1;
    if (summary.frames % kBodySeriesFrames == 0) {
      std::vector<scenes::SceneBody> bodies = scene.bodies(world);
      if (!bodies.empty()) summary.bodySeries.push_back({world.simulatedTime(), std::move(bodies)});
    }
    if (hooks.afterFrame) {
      const Clock::time_point hookStart = Clock::now();
      hooks.afterFrame(world, summary.frames);
      summary.hookSeconds += secondsSince(hookStart);
    }
    if (progress.due()) {
      const double cundall = summary.granuleSteps / std::max(secondsSince(loopStart), 1e-9);
      progress.show(progressText(frame + 1, frames, world, report, cundall, scene));
    }
  }
  summary.wallSeconds = secondsSince(loopStart) - summary.hookSeconds;
  progress.finish();
  if (hooks.atEnd) {
    const Clock::time_point hookStart = Clock::now();
    hooks.atEnd(world, summary.frames);
    summary.hookSeconds += secondsSince(hookStart);
  }

  summary.stats = world.readStats();
  summary.maxOverlap = std::max(summary.maxOverlap, summary.stats.maxOverlap);
  summary.bodies = world.readBodies();
  for (const BodyState& body : summary.bodies) {
    if (body.alive && body.granule && !scene.contains(body.position)) ++summary.granulesLost;
  }
  summary.gpuMemoryBytes = world.gpuMemoryBytes();
  summary.sceneFinished = scene.finished();
  summary.sceneMetrics = scene.metrics(summary.bodies);
  summary.sceneSeries = scene.series();
  summary.sceneBodies = scene.bodies(world);
  return summary;
}

int runHeadless(RunOptions& options) {
  const GpuContext gpu = GpuContext::headless();
  ProgressLine progress(!options.quiet);
  std::unique_ptr<Screenshots> screenshots;
  if (!options.screenshotPath.empty() || !options.screenshotDir.empty()) {
    screenshots = std::make_unique<Screenshots>(*options.scene, options.size,
                                                options.quality.value_or(render::kHighestQuality));
  }
  std::unique_ptr<SceneRecorder> recorder;
  if (!options.recordPath.empty()) {
    recorder = std::make_unique<SceneRecorder>(options.recordPath, *options.scene,
                                               options.scene->settings(), options.frameDt,
                                               options.snapshotEvery, gpu.description());
  }
  RunHooks hooks;
  if (recorder) hooks.afterBuild = [&](World& world, std::uint64_t) { recorder->begin(world); };
  if (!options.screenshotDir.empty() || recorder) {
    hooks.afterFrame = [&](World& world, std::uint64_t frame) {
      if (recorder) {
        recorder->recordFrame(world, *options.scene, static_cast<float>(options.frameDt), frame);
      }
      if (!options.screenshotDir.empty() && frame % options.every == 0) {
        screenshots->write(world, sequencePath(options.screenshotDir, frame));
      }
    };
  }
  std::uint64_t recordingBytes = 0;
  std::optional<LammpsExportSummary> lammps;
  if (!options.screenshotPath.empty() || recorder || !options.lammpsDir.empty()) {
    hooks.atEnd = [&](World& world, std::uint64_t) {
      if (recorder) recordingBytes = recorder->finish(world);
      if (!options.screenshotPath.empty()) screenshots->write(world, options.screenshotPath);
      if (!options.lammpsDir.empty())
        lammps = exportLammps(world, options.lammpsDir, lammpsOptions(*options.scene));
    };
  }
  const RunSummary summary = runScene(gpu, *options.scene, options.frames, options.frameDt,
                                      options.untilDone, progress, hooks);

  if (!options.metricsPath.empty()) {
    writeMetrics(options.metricsPath, metricsJson(summary, *options.scene));
  }
  char title[160];
  std::snprintf(title, sizeof title, "sandphys granules, scene %s, t = %.6f s",
                summary.scene.c_str(), summary.stats.simulatedTime);
  for (const std::filesystem::path& path : options.exportPaths) {
    exportGranules(path, summary.bodies, title);
  }
  if (!options.quiet) {
    std::fprintf(stderr,
                 "%s: %llu frames, %.3f s simulated in %.2f s wall (%llu steps of %.3g s), "
                 "%u granules, %u lost\n",
                 summary.scene.c_str(), static_cast<unsigned long long>(summary.frames),
                 summary.stats.simulatedTime, summary.wallSeconds,
                 static_cast<unsigned long long>(summary.stats.steps),
                 static_cast<double>(summary.timeStep), summary.stats.granulesAlive,
                 summary.granulesLost);
    const std::string status = options.scene->status();
    if (!status.empty()) std::fprintf(stderr, "%s: %s\n", summary.scene.c_str(), status.c_str());
    if (lammps) {
      std::fprintf(stderr,
                   "%s: LAMMPS deck %s: %u rigid clumps of %u particles, %u frozen particles, %u "
                   "walls, %u sinks, %zu lines on what does not map (run: lmp -in %s)\n",
                   summary.scene.c_str(), lammps->deck.string().c_str(), lammps->clumps,
                   lammps->clumpAtoms, lammps->frozenAtoms, lammps->walls, lammps->sinks,
                   lammps->notMapped.size(), lammps->deck.filename().string().c_str());
    }
    if (recorder) {
      const double seconds = std::max(summary.stats.simulatedTime, 1e-9);
      std::fprintf(stderr,
                   "%s: recorded %llu frames to %s: %llu bytes (%.1f kB per simulated s), "
                   "recording took %.2f s wall beside the run's %.2f s\n",
                   summary.scene.c_str(), static_cast<unsigned long long>(recorder->frames()),
                   options.recordPath.string().c_str(),
                   static_cast<unsigned long long>(recordingBytes), 1e-3 * recordingBytes / seconds,
                   recorder->ownSeconds(), summary.wallSeconds);
    }
    if (screenshots && screenshots->images() > 0) {
      const double simulationMs =
          1e3 * summary.wallSeconds / double(std::max<std::uint64_t>(summary.frames, 1));
      std::fprintf(stderr,
                   "%s: %llu images of %dx%d: render %.1f ms GPU each (%.2f s wall with read-back "
                   "and PNG in all); simulation %.1f ms wall per frame\n",
                   summary.scene.c_str(), static_cast<unsigned long long>(screenshots->images()),
                   options.size.width, options.size.height, screenshots->gpuMillisecondsPerImage(),
                   summary.hookSeconds, simulationMs);
    }
  }
  return kExitOk;
}

}  // namespace sandphys::samples
