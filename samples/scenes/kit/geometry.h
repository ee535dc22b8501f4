#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// kGranuleReach in float, as scenes compute their geometry: the largest distance from a
/// granule's centre to the surface of one of its particles, d.
inline constexpr float kReach = static_cast<float>(kGranuleReach);
/// Largest jitter of a block granule per axis, d (GranuleBlock's default jitter at the default
/// spacing).
inline const float kJitter = GranuleBlock{}.jitter * kDefaultGranuleSpacing;

/// Granules in a block of `counts`, in 64 bits so that a product of three counts cannot wrap.
inline std::uint64_t granuleCount(const Count3& counts) {
  return static_cast<std::uint64_t>(counts[0]) * counts[1] * counts[2];
}

/// Height between the lowest and the highest layer's centres of a block with `layers` layers at
/// `spacing` (m), m.
inline float blockSpan(std::uint32_t layers, float spacing) {
  return static_cast<float>(layers - 1) * spacing;
}

/// Angle between a body's up axis at the start (the template's y) and now, degrees, for an
/// orientation `q` (w, x, y, z): the world y component of the rotated y axis is 1 - 2 (x² + z²).
float tiltDegrees(const Quat& q);

/// A block of `counts` granules at `spacing` (m) centred on the y axis, its lowest lattice
/// centres `lift` (m) above y = 0: the bed or berm a scene's body acts on once it has settled.
GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed);

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

/// Whether `point` is inside `bounds`, faces included.
bool inBounds(const SceneBounds& bounds, const Vec3& point);

/// A box collider of `material` that holds the sand inside `bounds`.
Box containerBox(const SceneBounds& bounds, const SurfaceMaterial& material = {});

/// A smooth cylinder wall `radius` wide and `height` high (m) on a rough floor of particles `d`
/// wide (centres at y = 0), and a net one d under the floor: a grain that slips through the
/// floor's lattice (it should not) rests on the net instead of falling forever at maxSpeed.
void addCylinderContainer(World& world, float radius, float height, float d);

}  // namespace sandphys::scenes::kit
