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

/// Gap between a wall or floor and the nearest centres of a block of granules, d: a granule's
/// reach and jitter, with room.
inline constexpr float kLatticeGap = 1.4f;

/// Granules in a block of `counts`, in 64 bits so that a product of three counts cannot wrap.
inline std::uint64_t granuleCount(const Count3& counts) {
  return static_cast<std::uint64_t>(counts[0]) * counts[1] * counts[2];
}

/// Height between the lowest and the highest layer's centres of a block with `layers` layers at
/// `spacing` (m), m.
inline float blockSpan(std::uint32_t layers, float spacing) {
  return static_cast<float>(layers - 1) * spacing;
}

/// A block of `counts` granules at `spacing` (m) centred on the y axis, its lowest lattice
/// centres `lift` (m) above y = 0: the bed or berm a scene's body acts on once it has settled.
GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed);

/// Whether `point` is inside `bounds`, faces included.
bool inBounds(const SceneBounds& bounds, const Vec3& point);

/// A box collider of `material` that holds the sand inside `bounds`.
Box containerBox(const SceneBounds& bounds, const SurfaceMaterial& material = {});

/// A smooth cylinder wall `radius` wide and `height` high (m) on a rough floor of particles `d`
/// wide (centres at y = 0), and a net one d under the floor: a grain that slips through the
/// floor's lattice (it should not) rests on the net instead of falling forever at maxSpeed.
void addCylinderContainer(World& world, float radius, float height, float d);

}  // namespace sandphys::scenes::kit
