#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "sandphys/body.h"
#include "sandphys/math.h"
#include "sandphys/settings.h"
#include "sandphys/snapshot.h"

namespace sandphys::detail {

/// Throws InvalidArgument naming the first field of `settings` outside its range in
/// worldSettingFields() (the checks that involve one field alone).
void checkSettingRanges(const WorldSettings& settings);

/// Throws InvalidArgument naming `field` unless every component of `v` is finite.
void requireFiniteVec(const std::string& field, Vec3 v);

/// `q` scaled to unit length; throws InvalidArgument naming `field` for a zero or non-finite q.
Quat normalised(Quat q, const std::string& field);

/// Throws InvalidArgument unless a body reaching `reach` m beyond `position` lies where a float
/// still tells positions kMaxPositionSpacing particle diameters apart (`field` names it).
void requireResolvable(const std::string& field, Vec3 position, double reach,
                       float particleDiameter);

/// Throws InvalidArgument naming the field of a template that cannot make a body: no particles,
/// a non-finite offset, a mass, moment or bounding radius that is not finite and positive, a
/// principal rotation that is not a unit quaternion, or offsets beyond the bounding radius.
void requireTemplate(const ParticleTemplate& shape);

/// Throws InvalidArgument naming the slot and field of a snapshot that cannot be restored: a
/// non-finite position, velocity or spin, an orientation that is not a unit quaternion, a calm
/// count at or above 2^30, a negative or non-finite time, or a non-finite spring in a slot in use.
void requireRestorable(const WorldSnapshot& snapshot);

/// Particles of a RoughFloor lattice of `spacing` (m) over half extents hx, hz (m), or within
/// `radius` when it is > 0 (inRoughFloor): counted row by row before any is built, and only up
/// to `limit` (a larger count returns limit + 1), so that a floor of any size costs no memory.
std::uint64_t roughFloorParticles(double spacing, double hx, double hz, double radius,
                                  std::uint64_t limit);

/// How far, in spacings, a RoughFloor's lattice point may lie past its edge and still count: a
/// floor asked for in float metres (45 d at d = 0.02 m) reaches a little short of the points
/// meant to be on its edge, and must still get them.
inline constexpr double kRoughFloorEdgeTolerance = 1e-4;

/// The lattice steps of a RoughFloor from its centre to its edge `halfExtent` away (a whole
/// number; a double, so that a floor beyond any World is counted without overflow).
inline double roughFloorSteps(double halfExtent, double spacing) {
  return std::floor(halfExtent / spacing + kRoughFloorEdgeTolerance);
}

/// Whether the lattice point (px, pz) of a round RoughFloor of `radius` (> 0) belongs to it.
inline bool inRoughFloor(double px, double pz, double radius, double spacing) {
  const double reach = radius + kRoughFloorEdgeTolerance * spacing;
  return px * px + pz * pz <= reach * reach;
}

}  // namespace sandphys::detail
