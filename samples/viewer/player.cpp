#include "viewer/player.h"

#include <chrono>

namespace sandphys::viewer {

Player::Player(const GpuContext& gpu, const std::filesystem::path& file, FramePacer pacer)
    : m_file(file), m_playback(gpu, readRecording(file)), m_pacer(pacer) {}

bool Player::atEnd() const {
  return !m_playback.busy() && m_playback.shownFrame() == m_playback.frames();
}

void Player::frame(bool playing, bool step, FrameStats& stats) {
  stats.stepped = false;
  if ((playing || step) && !m_playback.busy() && !atEnd()) m_playback.playOn(1);
  if (!m_playback.busy()) return;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  // Playing, one recorded frame per viewer frame; catching up, as many as the budget allows.
  const std::optional<StepReport> report = m_playback.advance(m_pacer.budgetMs());
  if (!report) return;
  const double milliseconds =
      std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  recordStep(stats, world(), *report, milliseconds);
  stats.fullSubsteps = report->substeps;
  stats.timeScale = 1.0;
  m_pacer.recordStep(milliseconds, report->substeps);
}

}  // namespace sandphys::viewer
