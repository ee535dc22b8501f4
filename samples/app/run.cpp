#include "app/run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "app/export.h"
#include "app/metrics.h"

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

}  // namespace

RunSummary runScene(const GpuContext& gpu, scenes::Scene& scene, std::uint64_t frames,
                    double frameDt, bool untilDone, ProgressLine& progress) {
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

  const Clock::time_point loopStart = Clock::now();
  for (std::uint64_t frame = 0; frame < frames; ++frame) {
    if (untilDone && scene.finished()) break;
    const StepReport report = world.step(static_cast<float>(frameDt));
    // Count the granules this step moved before the scene may add the next batch.
    const std::uint32_t granules =
        report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
    summary.granuleSteps += static_cast<double>(granules) * report.substeps;
    summary.droppedSeconds += report.droppedTime;
    // The world resets its maximum overlap at every stats read, so the run's maximum is ours.
    if (report.hasStats) summary.maxOverlap = std::max(summary.maxOverlap, report.stats.maxOverlap);
    scene.update(world, report, world.simulatedTime());
    summary.frames = frame + 1;
    if (progress.due()) {
      const double cundall = summary.granuleSteps / std::max(secondsSince(loopStart), 1e-9);
      progress.show(progressText(frame + 1, frames, world, report, cundall, scene));
    }
  }
  summary.wallSeconds = secondsSince(loopStart);
  progress.finish();

  summary.stats = world.readStats();
  summary.maxOverlap = std::max(summary.maxOverlap, summary.stats.maxOverlap);
  summary.bodies = world.readBodies();
  for (const BodyState& body : summary.bodies) {
    if (body.alive && body.granule && !scene.contains(body.position)) ++summary.granulesLost;
  }
  summary.gpuMemoryBytes = world.gpuMemoryBytes();
  summary.sceneFinished = scene.finished();
  summary.sceneMetrics = scene.metrics(summary.bodies);
  return summary;
}

int runHeadless(RunOptions& options) {
  const GpuContext gpu = GpuContext::headless();
  ProgressLine progress(!options.quiet);
  const RunSummary summary =
      runScene(gpu, *options.scene, options.frames, options.frameDt, options.untilDone, progress);

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
  }
  return kExitOk;
}

}  // namespace sandphys::samples
