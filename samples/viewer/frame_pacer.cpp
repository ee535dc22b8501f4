#include "viewer/frame_pacer.h"

#include <algorithm>
#include <cmath>

namespace sandphys::viewer {

FramePacer::FramePacer(double budgetMs, std::optional<render::RenderQuality> fixedQuality)
    : m_fixedQuality(fixedQuality) {
  setBudgetMs(budgetMs);
}

void FramePacer::setBudgetMs(double milliseconds) {
  const render::RenderQuality before = quality();
  m_budgetMs = std::isfinite(milliseconds) ? std::max(milliseconds, 0.0) : 0.0;
  if (quality() != before) changeAutoQuality(m_autoQuality);
}

void FramePacer::setFixedQuality(std::optional<render::RenderQuality> fixed) {
  const render::RenderQuality before = quality();
  m_fixedQuality = fixed;
  // Auto goes on from what is on screen rather than from a choice made long ago.
  changeAutoQuality(before);
}

render::RenderQuality FramePacer::quality() const {
  if (m_fixedQuality) return *m_fixedQuality;
  return pacing() ? m_autoQuality : render::kHighestQuality;
}

std::uint32_t FramePacer::substepsFor(std::uint32_t fullSubsteps) const {
  const std::uint32_t full = std::max<std::uint32_t>(fullSubsteps, 1);
  if (!pacing()) return full;
  if (!(m_msPerSubstep > 0.0)) return 1;
  const double fit = std::floor((m_budgetMs - m_renderMs) / m_msPerSubstep);
  if (!(fit >= 1.0)) return 1;
  return fit >= static_cast<double>(full) ? full : static_cast<std::uint32_t>(fit);
}

void FramePacer::recordStep(double milliseconds, std::uint32_t substeps) {
  if (substeps == 0 || !std::isfinite(milliseconds) || milliseconds < 0.0) return;
  const double perSubstep = milliseconds / substeps;
  m_msPerSubstep = m_msPerSubstep > 0.0
                       ? (1.0 - kSmoothing) * m_msPerSubstep + kSmoothing * perSubstep
                       : perSubstep;
}

void FramePacer::recordDraw(double milliseconds, std::uint64_t measuredDraw,
                            std::uint64_t drawsDone) {
  m_drawsDone = drawsDone;
  if (measuredDraw <= m_lastMeasuredDraw || measuredDraw <= m_presetChangedAfterDraw) return;
  if (!std::isfinite(milliseconds) || milliseconds < 0.0) return;
  m_lastMeasuredDraw = measuredDraw;
  m_renderMs = milliseconds;
  if (m_fixedQuality || !pacing()) return;

  if (m_renderMs > kLowerAbove * m_budgetMs) {
    m_framesUnder = 0;
    m_framesOver = std::min(m_framesOver + 1, kFramesToLower);
    if (m_framesOver == kFramesToLower && m_autoQuality != render::kLowestQuality) {
      changeAutoQuality(render::lowerQuality(m_autoQuality));
    }
  } else if (m_renderMs < kRaiseBelow * m_budgetMs) {
    m_framesOver = 0;
    m_framesUnder = std::min(m_framesUnder + 1, kFramesToRaise);
    if (m_framesUnder == kFramesToRaise && m_autoQuality != render::kHighestQuality) {
      changeAutoQuality(render::higherQuality(m_autoQuality));
    }
  } else {
    m_framesOver = m_framesUnder = 0;
  }
}

void FramePacer::forgetStepCost() {
  m_msPerSubstep = 0.0;
}

void FramePacer::changeAutoQuality(render::RenderQuality quality) {
  m_autoQuality = quality;
  m_presetChangedAfterDraw = m_drawsDone;
  m_framesOver = m_framesUnder = 0;
}

}  // namespace sandphys::viewer
