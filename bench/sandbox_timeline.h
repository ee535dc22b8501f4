#pragma once

#include <cstdint>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::bench {

/// One frame of a sandbox run: what a game loop sees.
struct TimelineFrame {
  double simulatedSeconds = 0.0;  ///< at the end of the frame
  double wallMilliseconds = 0.0;  ///< the frame's substeps and its stats read-back
  std::uint32_t granulesAwake = 0;
  std::uint32_t granulesAsleep = 0;
};

/// The script of a sandbox run on a settled box pile, lengths in particle diameters d and times
/// in simulated seconds from its start: a ball dropped onto the pile at the start, then a
/// kinematic pusher that sinks into the sand, ploughs across it and is lifted out.
struct SandboxScript {
  float rockRadius = 3.0f;      ///< d
  float rockDropHeight = 5.0f;  ///< gap between the pile top and the ball's bottom, d
  float pusherRadius = 6.0f;    ///< d, as the viewer's pushing tool
  float pusherDepth = 4.0f;     ///< how far its bottom runs below the pile top, d
  double pushStart = 1.0;       ///< s: it starts to sink in, from above the sand
  double sinkSeconds = 0.4;     ///< s
  double ploughSeconds = 1.0;   ///< s, along z
  float ploughSpeed = 0.4f;     ///< m/s
  double frameSeconds = 1.0 / 60.0;
};

/// The particle centres of a ball: a lattice of spacing d inside `radius` d.
std::vector<Vec3> ballOffsets(float radius, float d);

/// Bodies and particles the script adds to a World of particle diameter `d`.
std::uint32_t sandboxBodies();
std::uint32_t sandboxParticles(const SandboxScript& script, float d);

/// Runs `seconds` of the script on `world`, a settled pile in a box of `side` (m, centred on
/// the y axis) whose top is at height `pileTop` (m): the ball lands at x = -side/4, the pusher
/// ploughs along z at x = side/4 from z = -0.3 side. In frames of script.frameSeconds (whole
/// substeps), each timed from a synchronised start to its stats read-back. Returns one entry per
/// frame.
std::vector<TimelineFrame> runSandbox(World& world, const SandboxScript& script, float side,
                                      float pileTop, double seconds);

}  // namespace sandphys::bench
