// Kinematic moves (World::moveKinematic): a straight path in whole substeps, placed by the World
// after every substep it covers, so that the pose at each substep is a function of the substep
// count alone, whatever frames drive the World.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

namespace {

// Substep counts beyond this are refused: far beyond any run, and exact in a double.
constexpr double kMaxMoveSubsteps = 0x1.0p52;

// The pose and velocity of `path` while the step count is `step` (startStep <= step <= endStep).
BodyDesc poseAt(const KinematicPath& path, std::uint64_t step) {
  const KinematicMove& m = path.move;
  BodyDesc desc{.position = m.to, .orientation = m.orientation, .motion = Motion::Kinematic};
  const std::uint64_t done = step - path.plan.startStep;
  const std::uint64_t steps = path.plan.endStep - path.plan.startStep;
  if (done >= steps) return desc;  // at `to` exactly, at rest
  // In double and rounded once, so that every substep's pose is the exact path's nearest float.
  const auto along = [&](float from, float to) {
    return float(double(from) + (double(to) - double(from)) * double(done) / double(steps));
  };
  desc.position = {along(m.from.x, m.to.x), along(m.from.y, m.to.y), along(m.from.z, m.to.z)};
  desc.velocity = path.plan.velocity;
  return desc;
}

}  // namespace

KinematicMovePlan World::moveKinematic(BodyId id, const KinematicMove& move) {
  Impl& w = impl();
  w.requireBody(id);
  const std::uint32_t slot = w.slotOf(id.index);
  const Motion motion = w.bodyMotions[slot];
  if (motion != Motion::Kinematic) {
    throw InvalidArgument("World::moveKinematic: body " + std::to_string(id.index) +
                          " has motion " + std::to_string(unsigned(motion)) +
                          " (0 dynamic, 1 kinematic, 2 static): only a Motion::Kinematic body "
                          "follows a move");
  }
  requireFiniteVec("KinematicMove.from", move.from);
  requireFiniteVec("KinematicMove.to", move.to);
  const float d = w.settings.particleDiameter;
  requireResolvable("KinematicMove.from", move.from, w.boundingRadii[slot], d);
  requireResolvable("KinematicMove.to", move.to, w.boundingRadii[slot], d);
  const double dt = w.model.timeStep;
  requireNonNegative("KinematicMove.duration", move.duration, "(s)");
  require(move.duration / dt < kMaxMoveSubsteps, "KinematicMove.duration", move.duration,
          "must be < 2^52 substeps of " + formatValue(dt) + " s");
  requireFinite("KinematicMove.startTime", move.startTime);
  require(move.startTime / dt < kMaxMoveSubsteps, "KinematicMove.startTime", move.startTime,
          "must be < 2^52 substeps of " + formatValue(dt) + " s");
  const double start = std::ceil(move.startTime / dt);
  require(start >= double(w.steps), "KinematicMove.startTime", move.startTime,
          "must not be in the past: the World is at " + formatValue(w.simTime) + " s (substep " +
              std::to_string(w.steps) +
              "), and a move starts at the first substep at or after its startTime");

  KinematicPath path;
  path.body = slot;
  path.move = move;
  path.move.orientation = normalised(move.orientation, "KinematicMove.orientation");
  const auto steps = std::max<std::uint64_t>(1, std::uint64_t(std::llround(move.duration / dt)));
  path.plan.startStep = std::uint64_t(start);
  path.plan.endStep = path.plan.startStep + steps;
  const double seconds = double(steps) * dt;
  path.plan.velocity = {float((double(move.to.x) - double(move.from.x)) / seconds),
                        float((double(move.to.y) - double(move.from.y)) / seconds),
                        float((double(move.to.z) - double(move.from.z)) / seconds)};

  const auto same = [&](const KinematicPath& p) { return p.body == slot; };
  std::erase_if(w.moves, same);
  w.moves.push_back(path);
  w.movesEnd = 0;
  for (const KinematicPath& p : w.moves) w.movesEnd = std::max(w.movesEnd, p.plan.endStep);
  // A move that starts now places the body now; any other is placed by the substeps.
  if (path.plan.startStep == w.steps) {
    w.gpu->makeCurrent();
    w.placeBody(path.body, poseAt(path, w.steps));
  }
  return path.plan;
}

void World::Impl::followMoves() {
  if (moves.empty() || steps > movesEnd) return;
  for (const KinematicPath& path : moves) {
    if (steps < path.plan.startStep || steps > path.plan.endStep) continue;
    placeBody(path.body, poseAt(path, steps));
  }
}

}  // namespace sandphys
