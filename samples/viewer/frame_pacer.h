#pragma once

#include <cstdint>
#include <optional>

#include "render/render_quality.h"

namespace sandphys::viewer {

/// Keeps the viewer interactive when a whole frame of simulation costs more than a frame should:
/// within a wall-clock budget per frame it picks how many substeps the next frame runs (fewer
/// than a whole frame dt needs means slow motion) and, in auto quality, the renderer's preset.
/// Pure bookkeeping on measured times; no GL.
class FramePacer {
 public:
  /// Weight of the newest frame in the smoothed cost of a substep, in (0, 1]: one slow frame
  /// (a tool adding its sphere, the OS stealing the CPU) moves the estimate by a quarter only.
  static constexpr double kSmoothing = 0.25;

  // Auto quality. A preset one step dearer draws 1.8 to 2.3 times the pixels (render scale 0.5 ->
  // 0.75 -> 1) with more AO samples, so its render time is about 2 to 3 times the cheaper one's.
  // Lowering happens above half the budget; raising only below kRaiseBelow of it, where even
  // three times the render time stays under the lowering threshold, so a raise is not undone by
  // the next measurement. Both wait for several consecutive frames, so that one slow frame does
  // not switch, and raising waits longer, because a raise that was wrong costs visible stutter.

  /// Auto quality lowers the preset when the render time exceeds this fraction of the budget...
  static constexpr double kLowerAbove = 0.5;
  /// ...in this many consecutive measured frames.
  static constexpr int kFramesToLower = 5;
  /// Auto quality raises the preset when the render time stays below this fraction of the
  /// budget...
  static constexpr double kRaiseBelow = 0.15;
  /// ...in this many consecutive measured frames.
  static constexpr int kFramesToRaise = 30;

  /// No budget (every frame simulates its whole frame dt), auto quality.
  FramePacer() = default;
  /// `budgetMs` as setBudgetMs takes it; `fixedQuality` empty for auto.
  FramePacer(double budgetMs, std::optional<render::RenderQuality> fixedQuality);

  /// Wall-clock time one frame may take, ms; >= 0, where 0 turns pacing off (every frame then
  /// simulates its whole frame dt and auto quality draws high). A negative or non-finite value
  /// is taken as 0.
  void setBudgetMs(double milliseconds);
  double budgetMs() const { return m_budgetMs; }
  /// Whether a budget applies (budgetMs > 0).
  bool pacing() const { return m_budgetMs > 0.0; }

  /// Fixes the renderer's preset, or hands it to auto (empty), which starts from the preset in
  /// use.
  void setFixedQuality(std::optional<render::RenderQuality> quality);
  /// The preset the user fixed; empty in auto.
  std::optional<render::RenderQuality> fixedQuality() const { return m_fixedQuality; }
  /// The preset the renderer should draw the next frame with: the fixed one, or auto's choice
  /// (high without a budget).
  render::RenderQuality quality() const;

  /// Substeps the next frame should run when a whole frame dt is `fullSubsteps` (>= 1): without a
  /// budget, all of them; with one, as many as fill (budget - render time) at the smoothed cost
  /// of a substep, at least 1 and at most `fullSubsteps`. Before any step was measured, 1: a new
  /// scene can cost anything, and one substep is the cheapest way to find out.
  std::uint32_t substepsFor(std::uint32_t fullSubsteps) const;

  /// Feeds a finished World::step: its wall time, ms, and the substeps it ran. A step that ran
  /// none (its time was only overhead) teaches nothing about the cost of a substep.
  void recordStep(double milliseconds, std::uint32_t substeps);
  /// Feeds the renderer's newest times: `milliseconds` for all passes of draw number
  /// `measuredDraw` (RenderStats::frame, counted from 1), with `drawsDone` draws issued so far.
  /// A measurement seen before, or of a draw made before the preset last changed, is ignored.
  void recordDraw(double milliseconds, std::uint64_t measuredDraw, std::uint64_t drawsDone);
  /// Forgets the cost of a substep (a new World or scene costs differently); the budget, the
  /// render times and the preset stay.
  void forgetStepCost();

  /// Smoothed wall time of one substep, ms; 0 before the first measurement.
  double msPerSubstep() const { return m_msPerSubstep; }
  /// Newest render time measured at the preset in use (or the one before, until a draw at the
  /// new preset was measured), ms; 0 before the first.
  double renderMs() const { return m_renderMs; }

 private:
  void changeAutoQuality(render::RenderQuality quality);

  double m_budgetMs = 0.0;
  std::optional<render::RenderQuality> m_fixedQuality;
  render::RenderQuality m_autoQuality = render::kHighestQuality;
  double m_msPerSubstep = 0.0;
  double m_renderMs = 0.0;
  std::uint64_t m_drawsDone = 0;
  std::uint64_t m_lastMeasuredDraw = 0;
  // Draws up to this number were made at an earlier preset.
  std::uint64_t m_presetChangedAfterDraw = 0;
  int m_framesOver = 0;
  int m_framesUnder = 0;
};

}  // namespace sandphys::viewer
