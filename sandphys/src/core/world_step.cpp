// The frame: World::step's accumulator of fixed substeps (and the idle ones it skips), and
// World::substep.
#include "sandphys/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "core/log.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

StepReport World::step(float frameDt) {
  return step(frameDt, std::numeric_limits<std::uint64_t>::max());
}

StepReport World::step(float frameDt, std::uint64_t stopAt) {
  Impl& w = impl();
  StepReport report;
  if (!std::isfinite(frameDt) || frameDt < 0.0f) return report;
  if (frameDt == 0.0f && w.heldSubsteps == 0) return report;
  w.gpu->makeCurrent();
  w.takeIdleHint();
  w.accumulator += frameDt;
  const double dt = w.model.timeStep;
  // Compared in double before any integer conversion: a frame of more substeps than an integer
  // holds is dropped like any other beyond the cap, never wrapped to none.
  const double fresh = std::floor(w.accumulator / dt);
  const double needed = double(w.heldSubsteps) + fresh;
  std::uint64_t due = 0;
  if (needed > double(w.settings.maxSubstepsPerFrame)) {
    report.droppedTime = float((needed - w.settings.maxSubstepsPerFrame) * dt);
    if (!w.warnedDroppedTime) {
      char message[320];
      std::snprintf(message, sizeof message,
                    "a frame of %.4g s needs %.4g substeps of %.3g s, more than "
                    "WorldSettings.maxSubstepsPerFrame = %u; the rest is dropped (slow motion). "
                    "This warning is given once; StepReport::droppedTime has every frame's.",
                    double(frameDt), needed, dt, w.settings.maxSubstepsPerFrame);
      log(LogLevel::Warning, message);
      w.warnedDroppedTime = true;
    }
    due = w.settings.maxSubstepsPerFrame;
    w.accumulator = 0.0;
  } else {
    due = std::uint64_t(needed);
    w.accumulator -= fresh * dt;
  }
  // Whatever lies beyond stopAt waits, counted, for the next call.
  const std::uint64_t room = stopAt > w.steps ? stopAt - w.steps : 0;
  const std::uint64_t run = std::min(due, room);
  w.heldSubsteps = due - run;
  report.initialOverlaps = w.checkInitialOverlaps();
  w.resetPeakOverlap();
  if (w.profiler.enabled()) w.profiler.resetTotals();
  w.buffers.bindAll();
  const bool statsWereCurrent = w.statsCurrent;
  const bool peaksWereClear = w.peaksClear;
  // Nothing changed since a substep that computed nothing: this frame's would not either. Dirty
  // parameters (a collider or sink changed) were uploaded by the reset above, which cleared
  // idleSinceCheck; a build the CPU asks for makes the lists stale without changing a body.
  const bool idleThrough = w.idleSinceCheck && !w.listsStale && w.idleSubstepsRepeat();
  std::uint64_t done = 0;
  while (!idleThrough && done < run) {
    w.emit(dt, &report);
    w.runSubstep();
    w.followMoves();
    ++done;
    // Sand that slept through the last frame: if this first substep computed nothing either, the
    // rest would not, and would change no bit (nothing the CPU does comes between them).
    if (done == 1 && run > 1 && w.sandLooksIdle && w.idleSubstepsRepeat()) {
      w.sandLooksIdle = w.lastSubstepComputedNothing();
      if (w.sandLooksIdle) {
        w.substepChangedNothing(statsWereCurrent, peaksWereClear);
        break;
      }
    }
  }
  w.startIdleHint(done);
  report.idleSubsteps = std::uint32_t(run - done);
  for (; done < run; ++done) w.advanceClock();
  report.substeps = std::uint32_t(run);
  report.simulatedTime = float(double(run) * dt);
  report.substepsHeld = std::uint32_t(w.heldSubsteps);
  if (w.profiler.enabled()) w.profiler.collect();
  if (w.settings.statsEachFrame) {
    report.stats = w.readStats();
    report.hasStats = true;
  }
  return report;
}

bool World::Impl::idleSubstepsRepeat() const {
  const bool emitting =
      std::ranges::any_of(emitters, [](const auto& e) { return e && !e->finished(); });
  return sleep.enabled && !emitting && (moves.empty() || steps > movesEnd);
}

bool World::Impl::computedNothing(std::span<const std::uint32_t> counters) {
  const auto listed = [&](ActivePass pass) {
    return counters[kCounterActiveDispatch + 4 * pass + 3];  // the list's length
  };
  return listed(kActivePassContacts) == 0 && listed(kActivePassBodies) == 0;
}

bool World::Impl::lastSubstepComputedNothing() {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  buffers[kCounters].download(0, sizeof counters, counters.data());
  return computedNothing(counters);
}

void World::Impl::takeIdleHint() {
  std::array<std::uint32_t, kCounterCount> hinted{};
  if (idleHint.take(hinted.data())) sandLooksIdle = computedNothing(hinted);
}

void World::Impl::startIdleHint(std::uint64_t substepsRun) {
  // The statistics of each frame tell it already (reduceStats), and a frame found idle needs none.
  if (!sleep.enabled || settings.statsEachFrame || substepsRun == 0 || idleSinceCheck) return;
  idleHint.start(buffers[kCounters], 0, sizeof counters);
}

void World::Impl::substepChangedNothing(bool statsWereCurrent, bool peaksWereClear) {
  // It wrote no overlap, and changed nothing the statistics read unless it built lists.
  peaksClear = peaksWereClear;
  idleSinceCheck = true;
  const auto built = [&](std::uint32_t counter, std::uint64_t reduced) {
    return counters[counter] != std::uint32_t(reduced);
  };
  statsCurrent = statsWereCurrent && !built(kCounterListBuilds, reducedStats.listBuilds) &&
                 !built(kCounterStillBuilds, reducedStats.stillGridBuilds);
}

void World::substep(std::uint32_t count) {
  Impl& w = impl();
  w.gpu->makeCurrent();
  if (count > 0) w.checkInitialOverlaps();
  if (w.profiler.enabled()) w.profiler.resetTotals();
  w.buffers.bindAll();
  for (std::uint32_t i = 0; i < count; ++i) {
    w.emit(w.model.timeStep, nullptr);
    w.runSubstep();
    w.followMoves();
  }
  if (w.profiler.enabled()) w.profiler.collect();
}

}  // namespace sandphys
