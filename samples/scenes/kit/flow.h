#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::scenes::kit {

/// A run of `count` lattice columns along x, from x = first at z = row, in lattice spacings.
struct LatticeRun {
  std::int32_t row, first;
  std::uint32_t count;
};

/// The `columns` columns of a square lattice nearest its axis (x = z = 0), as one run per row in
/// z order: ties in distance go to the lower row, then the lower column, so that each row's share
/// is one run.
std::vector<LatticeRun> discRuns(std::uint32_t columns);

/// Largest distance of a column of `runs` from the axis, in lattice spacings.
double discRadius(std::span<const LatticeRun> runs);

/// A smooth cylinder wall `radius` wide and `height` high (m) on a rough floor of particles `d`
/// wide (centres at y = 0), and a net one d under the floor: a grain that slips through the
/// floor's lattice (it should not) rests on the net instead of falling forever at maxSpeed.
void addCylinderContainer(World& world, float radius, float height, float d);

}  // namespace sandphys::scenes::kit
