#pragma once

// A World's state as LAMMPS sees it (lammps_export.cpp writes it out): spheres, the rigid clumps
// they form and the bounds of the scene. Read from the GPU once.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sandphys/world.h"

namespace sandphys::detail {

using Vec3d = std::array<double, 3>;

/// One particle.
struct LammpsAtom {
  Vec3d position{};            // m
  std::uint32_t molecule = 0;  // its clump's molecule ID (1-based), 0 for a frozen particle
  double mass = 0.0;           // kg
};

/// One rigid clump: an alive granule or dynamic body.
struct LammpsClump {
  std::uint32_t slot = 0;  // body slot
  double mass = 0.0;       // kg
  Vec3d centre{};          // centre of mass, m
  // Inertia tensor about the centre of mass in the world frame, kg m²: xx, yy, zz, xy, xz, yz.
  std::array<double, 6> inertia{};
  Vec3d velocity{};         // m/s
  Vec3d angularMomentum{};  // kg m²/s, world frame
};

struct LammpsScene {
  std::vector<LammpsAtom> atoms;  // clumps' particles first (molecule order), then the frozen
  std::vector<LammpsClump> clumps;
  std::uint32_t clumpAtoms = 0;
  std::uint32_t staticBodies = 0;
  std::uint32_t kinematicBodies = 0;
  std::uint32_t deadBodies = 0;
  std::uint32_t sleepingGranules = 0;
  double largestClumpRadius = 0.0;  // farthest particle centre from a clump's centre of mass, m
  Vec3d lo{}, hi{};                 // bounds of every particle centre, m
};

/// Every body slot of `world` in use: alive granules and dynamic bodies as clumps, static and
/// kinematic bodies as frozen particles, dead ones left out. Particles are placed from their
/// bodies' stored poses (as the next substep places them). Sync point.
LammpsScene gatherLammpsScene(const World& world);

}  // namespace sandphys::detail
