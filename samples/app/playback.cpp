// --play's timeline: the recording re-simulated in order and checked, recorded snapshots shown
// for the frames behind, and the re-simulated state put aside meanwhile.
#include "app/playback.h"

#include <algorithm>
#include <chrono>

namespace sandphys::samples {

Playback::Playback(const GpuContext& gpu, Recording recording)
    : m_gpu(gpu), m_recording(std::move(recording)) {
  m_run = std::make_unique<ReplayRun>(m_gpu, m_recording);
  check();
}

void Playback::check() {
  std::optional<ReplayRun::Difference> difference = m_run->checkFrame();
  const std::uint64_t frame = m_run->frame();
  m_checked = std::max(m_checked, frame);
  if (!difference || (m_mismatch && m_mismatch->frame <= frame)) return;
  std::string what = std::move(difference->what);
  if (difference->hashOnly) {
    what += " (the frame has no snapshot: --replay names the body and field at the next one)";
  }
  m_mismatch = Mismatch{frame, what + deviceCaveat(m_gpu, m_recording)};
}

void Playback::putBack() {
  if (!m_aside) return;
  m_run->world().restoreSnapshot(*m_aside);
  m_aside.reset();
  m_shown = m_run->frame();
}

void Playback::scrubTo(std::uint64_t frame) {
  frame = std::min(frame, frames());
  m_rebuild = false;
  const std::uint64_t simulated = m_run->frame();
  if (frame == simulated) {
    putBack();
    m_target = frame;
    return;
  }
  // The latest snapshot at or before the frame whose bodies the World already has: bodies are
  // added in the same order every time, so its slot i is the World's. One taken after bodies were
  // added (a batch, an emitter's) waits until the re-simulation has added them.
  const std::size_t slots = m_run->world().bodyCount();
  const WorldSnapshot* shown = nullptr;
  for (const WorldSnapshot& snapshot : m_recording.snapshots) {
    if (snapshot.frame <= frame && snapshot.bodies.size() <= slots &&
        (!shown || snapshot.frame > shown->frame)) {
      shown = &snapshot;
    }
  }
  if (frame > simulated && (!shown || shown->frame <= simulated)) {
    putBack();
    m_target = frame;
    return;
  }
  if (!shown) {
    // Nothing recorded to show: only the re-simulation from the start gets there.
    m_rebuild = true;
    m_target = frame;
    return;
  }
  if (!m_aside) m_aside = m_run->world().readSnapshot();
  m_run->world().restoreSnapshot(*shown);
  m_shown = shown->frame;
  m_target = m_shown;
}

void Playback::playOn(std::uint64_t count) {
  const std::uint64_t target = std::min(m_shown + count, frames());
  if (m_aside && m_shown < m_run->frame()) {
    m_rebuild = true;
    m_target = target;
    return;
  }
  // From the re-simulated state, or from a snapshot ahead of it: the re-simulation goes on.
  putBack();
  m_target = target;
}

std::optional<std::uint64_t> Playback::snapshotBefore() const {
  std::optional<std::uint64_t> before;
  for (const WorldSnapshot& snapshot : m_recording.snapshots) {
    if (snapshot.frame < m_shown && (!before || snapshot.frame > *before)) before = snapshot.frame;
  }
  return before;
}

std::optional<std::uint64_t> Playback::snapshotAfter() const {
  std::optional<std::uint64_t> after;
  for (const WorldSnapshot& snapshot : m_recording.snapshots) {
    if (snapshot.frame > m_shown && (!after || snapshot.frame < *after)) after = snapshot.frame;
  }
  return after;
}

std::optional<StepReport> Playback::advance(double budgetMilliseconds) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  if (m_rebuild) {
    m_rebuild = false;
    m_aside.reset();
    // The old World goes first: two full-size worlds need not fit in memory at once.
    m_run.reset();
    m_run = std::make_unique<ReplayRun>(m_gpu, m_recording);
    m_shown = 0;
    check();
  }
  if (m_aside) return std::nullopt;
  std::optional<StepReport> last;
  while (m_run->frame() < m_target) {
    last = m_run->stepFrame();
    check();
    m_shown = m_run->frame();
    const double spent = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (spent >= budgetMilliseconds) break;
  }
  return last;
}

}  // namespace sandphys::samples
