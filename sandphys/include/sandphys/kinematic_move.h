#pragma once

#include <cstdint>

#include "sandphys/math.h"

namespace sandphys {

/// A straight move of a Motion::Kinematic body at constant velocity, scripted in simulated time
/// and run by the World substep by substep (World::moveKinematic), so that it starts and ends on
/// exact substeps whatever frame lengths drive the World.
///
/// Times become substeps by one rule: the move starts at the first substep at or after
/// `startTime` (S = ceil(startTime / timeStep)) and lasts round(duration / timeStep) substeps,
/// at least one (N). While stepCount() is S + k, 0 <= k <= N, the body's centre of mass is
/// from + (to - from) · k / N (computed in double, rounded once to float; exactly `to`, bit for
/// bit, at k = N), its orientation `orientation`, its velocity (to - from) / (N · timeStep) and
/// its spin zero; from S + N on its velocity is zero and it stays at `to`. Before S the body is
/// as it was last set.
struct KinematicMove {
  /// Centre of mass at the start, m; finite.
  Vec3 from{};
  /// Centre of mass at the end, m; finite. The body lands on it bit for bit.
  Vec3 to{};
  /// Orientation of the body's template frame throughout (normalised; a zero one is refused).
  Quat orientation{};
  /// Simulated time at which the move starts, s; finite and not before World::simulatedTime().
  double startTime = 0.0;
  /// Length of the move, s; finite and >= 0 (0 jumps in one substep).
  double duration = 0.0;
};

/// The substeps a KinematicMove was given (World::moveKinematic), as World::stepCount counts.
struct KinematicMovePlan {
  /// Substep at which the move starts: stepCount() when the body is at `from`.
  std::uint64_t startStep = 0;
  /// Substep at which it ends: stepCount() when the body is at `to`, at rest.
  std::uint64_t endStep = 0;
  /// The body's velocity during the move, m/s.
  Vec3 velocity{};
};

}  // namespace sandphys
