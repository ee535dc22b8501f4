#pragma once

#include <cstdint>

#include "sandphys/ids.h"
#include "sandphys/readback.h"

namespace sandphys {

/// Overlap, in particle diameters, beyond which a body placed by the CPU counts as placed inside
/// something (the paper's penetration guard, d/10): far beyond the overlaps of sand at rest.
inline constexpr float kInitialOverlapTolerance = 0.1f;

/// Bodies added from the CPU (World::addBody, addGranules, addRoughFloor) that start inside
/// another body or a collider: checked once, at the first step or substep after they were added
/// (a sync point then: the deep contacts of their particles are listed on the GPU and read back),
/// and printed as a warning when any are found.
struct InitialOverlaps {
  /// Particles of the added bodies overlapping something by more than kInitialOverlapTolerance d.
  std::uint32_t particles = 0;
  /// The deepest of those overlaps, m; 0 when there is none.
  float worstOverlap = 0.0f;
  /// The added body of the deepest overlap, and what it overlaps: another body or a collider
  /// (the other id is invalid).
  BodyId body{};
  BodyId otherBody{};
  ColliderId collider{};
};

/// What one World::step did. `stats` is filled only when WorldSettings::statsEachFrame is on.
struct StepReport {
  std::uint32_t substeps = 0;  ///< fixed substeps run
  /// Of those, the substeps that did no GPU work: with sleep, once the first substep of the frame
  /// found every body asleep and untouched (and no emitter or kinematic move running), the rest
  /// would have computed nothing and changed no bit; only the time and the substep count
  /// advance. The frame checks its first substep when the last frame ended that way (its
  /// statistics, a readStats, or without WorldSettings::statsEachFrame a copy of the counters
  /// taken when ready). The frames after such a frame skip every substep, until the CPU changes
  /// something. World::substep runs every substep.
  std::uint32_t idleSubsteps = 0;
  float simulatedTime = 0.0f;  ///< substeps · timeStep, s
  float droppedTime = 0.0f;    ///< frame time discarded by the substep cap, s
  /// Substeps due but not run because the step stopped at its stopAt (World::step(frameDt,
  /// stopAt)): the next step runs them first. 0 for a step without stopAt.
  std::uint32_t substepsHeld = 0;
  std::uint32_t granulesEmitted = 0;
  bool emitterBlocked = false;  ///< an emitter wanted to add granules but capacity was full
  bool hasStats = false;
  WorldStats stats{};
  /// Bodies added since the previous step that start overlapping (all zero when none were added
  /// or none overlap).
  InitialOverlaps initialOverlaps{};

  /// Adds `later`, the report of the next part of a frame run in parts (a step that held
  /// substeps, then the steps that ran them), so that the frame reads as one: counts and times
  /// add up; the held substeps and the stats are the later part's; the initial overlaps are the
  /// first part's that found any.
  void append(const StepReport& later) {
    substeps += later.substeps;
    idleSubsteps += later.idleSubsteps;
    simulatedTime += later.simulatedTime;
    droppedTime += later.droppedTime;
    substepsHeld = later.substepsHeld;
    granulesEmitted += later.granulesEmitted;
    emitterBlocked = emitterBlocked || later.emitterBlocked;
    if (later.hasStats) {
      hasStats = true;
      stats = later.stats;
    }
    if (initialOverlaps.particles == 0) initialOverlaps = later.initialOverlaps;
  }
};

}  // namespace sandphys
