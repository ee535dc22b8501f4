#include "sandbox_timeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sandphys::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Where the pusher is and how it moves at time t of the script: above the sand before it
// starts and after it is lifted out, moving only while it sinks and ploughs.
struct PusherPose {
  Vec3 position;
  Vec3 velocity;
};

PusherPose pusherAt(const SandboxScript& s, float d, float side, float pileTop, double t) {
  const float ploughY = pileTop + (s.pusherRadius - s.pusherDepth) * d;
  const float aboveY = pileTop + (s.pusherRadius + 2.0f) * d;
  const float x = 0.25f * side;
  const float startZ = -0.3f * side;
  const double sinkEnd = s.pushStart + s.sinkSeconds;
  const double ploughEnd = sinkEnd + s.ploughSeconds;
  if (t < s.pushStart || t >= ploughEnd) {
    const float z = t < s.pushStart ? startZ : startZ + float(s.ploughSeconds) * s.ploughSpeed;
    return {{x, aboveY + 20.0f * d, z}, {}};
  }
  if (t < sinkEnd) {
    const float speed = (aboveY - ploughY) / float(s.sinkSeconds);
    return {{x, aboveY - speed * float(t - s.pushStart), startZ}, {0.0f, -speed, 0.0f}};
  }
  return {{x, ploughY, startZ + s.ploughSpeed * float(t - sinkEnd)}, {0.0f, 0.0f, s.ploughSpeed}};
}

}  // namespace

std::vector<Vec3> ballOffsets(float radius, float d) {
  std::vector<Vec3> offsets;
  const int n = int(radius);
  for (int x = -n; x <= n; ++x)
    for (int y = -n; y <= n; ++y)
      for (int z = -n; z <= n; ++z)
        if (x * x + y * y + z * z <= n * n) offsets.push_back({x * d, y * d, z * d});
  return offsets;
}

std::uint32_t sandboxBodies() {
  return 2;
}

std::uint32_t sandboxParticles(const SandboxScript& script, float d) {
  return std::uint32_t(ballOffsets(script.rockRadius, d).size() +
                       ballOffsets(script.pusherRadius, d).size());
}

std::vector<TimelineFrame> runSandbox(World& world, const SandboxScript& script, float side,
                                      float pileTop, double seconds) {
  const float d = world.settings().particleDiameter;
  const float density = world.settings().material.density;
  world.addBody(
      makeParticleTemplate(ballOffsets(script.rockRadius, d), d, density),
      {.position = {-0.25f * side, pileTop + (script.rockDropHeight + script.rockRadius) * d, 0.0f},
       .motion = Motion::Dynamic});
  const PusherPose parked = pusherAt(script, d, side, pileTop, 0.0);
  const BodyId pusher =
      world.addBody(makeParticleTemplate(ballOffsets(script.pusherRadius, d), d, density),
                    {.position = parked.position, .motion = Motion::Kinematic});

  const auto substeps =
      std::uint32_t(std::max(1.0, std::round(script.frameSeconds / double(world.timeStep()))));
  const double frame = substeps * double(world.timeStep());
  std::vector<TimelineFrame> frames;
  world.readStats();  // a synchronised start
  bool moving = false;
  for (double t = 0.0; t < seconds - 0.5 * frame; t += frame) {
    const Clock::time_point start = Clock::now();
    const PusherPose pose = pusherAt(script, d, side, pileTop, t);
    const bool movesNow =
        pose.velocity.x != 0.0f || pose.velocity.y != 0.0f || pose.velocity.z != 0.0f;
    // Set while it moves, and once when it stops (lifted out); untouched while parked.
    if (movesNow || moving) {
      world.setBodyState(
          pusher,
          {.position = pose.position, .velocity = pose.velocity, .motion = Motion::Kinematic});
    }
    moving = movesNow;
    world.substep(substeps);
    const WorldStats stats = world.readStats();
    TimelineFrame entry;
    entry.simulatedSeconds = t + frame;
    entry.wallMilliseconds =
        std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    entry.granulesAsleep = stats.granulesAsleep;
    entry.granulesAwake = stats.granulesAlive - stats.granulesAsleep;
    frames.push_back(entry);
  }
  return frames;
}

}  // namespace sandphys::bench
