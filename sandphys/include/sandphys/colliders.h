#pragma once

#include <cstdint>

#include <variant>

#include "sandphys/math.h"
#include "sandphys/settings.h"

namespace sandphys {

/// How a collider's surface moves: contacts see the surface velocity v + ω × (x - reference) at
/// the contact point x (at the particle's centre under ContactLaw::PaperViscous), for damping and
/// friction (a rising gate, a plunger, a conveyor). The
/// reference point is the box's centre, the cylinder's base, the funnel's outlet centre, or the
/// plane's point nearest the origin. The pose itself changes only when World::setCollider or
/// World::moveCollider gives a new one.
struct ColliderMotion {
  Vec3 velocity{};         ///< m/s
  Vec3 angularVelocity{};  ///< rad/s, world frame
};

/// A smooth, infinite half-space: solid where dot(normal, x) < offset. normal need not be unit
/// (it is normalised) but must be non-zero.
struct Plane {
  Vec3 normal{0.0f, 1.0f, 0.0f};
  float offset = 0.0f;  ///< m
  SurfaceMaterial material{};
  ColliderMotion motion{};
};

/// A smooth oriented box. inside = true: a closed container whose six walls keep grains in (a
/// particle found outside, e.g. pushed through a wall, is pushed back in: do not place sand
/// outside a container box); inside = false: a solid obstacle that keeps grains out.
struct Box {
  Vec3 center{};
  Vec3 halfExtents{0.5f, 0.5f, 0.5f};  ///< m, each > 0
  Quat orientation{};
  bool inside = true;
  SurfaceMaterial material{};
  ColliderMotion motion{};
};

/// A smooth, thin vertical cylinder wall (axis along y) from base.y to base.y + height; open at
/// both ends (add a Plane or a rough floor for the bottom).
struct Cylinder {
  Vec3 base{};
  float radius = 1.0f;  ///< m, > 0
  float height = 1.0f;  ///< m, > 0
  SurfaceMaterial material{};
  ColliderMotion motion{};
};

/// A smooth, thin cone wall around a vertical axis (the hourglass funnel of the paper's
/// Fig. 16): radius outletRadius at y = outletCenter.y widening upward at halfAngle from the
/// axis to height outletCenter.y + height. The outlet is an open hole.
struct Funnel {
  Vec3 outletCenter{};
  float outletRadius = 0.1f;    ///< m, >= 0
  float halfAngle = 0.785398f;  ///< rad, in (0, π/2)
  float height = 1.0f;          ///< m, > 0
  SurfaceMaterial material{};
  ColliderMotion motion{};
};

/// Any implicit collider, as given to World::addCollider or World::setCollider (see
/// World::colliders).
using ColliderShape = std::variant<Plane, Box, Cylinder, Funnel>;

/// A rough floor: a static body of particles (diameter of the world) on a square lattice of
/// spacing `spacing` in the plane y = center.y, inside a disc (radius > 0) or a rectangle
/// (halfExtentX/Z). Rough = the grains touch particles, so they can lock on it.
struct RoughFloor {
  Vec3 center{};
  float radius = 0.0f;       ///< m; > 0 selects a disc
  float halfExtentX = 0.0f;  ///< m; used when radius == 0
  float halfExtentZ = 0.0f;  ///< m; used when radius == 0
  float spacing = 0.0f;      ///< m; 0 means one particle diameter
};

/// Particles World::addRoughFloor places for `floor` in a World of particles `particleDiameter`
/// (m) wide: the lattice points within its disc, or its rectangle when the radius is 0. For
/// sizing WorldSettings::maxParticles exactly; counted row by row, so any size is cheap.
std::uint64_t roughFloorParticles(const RoughFloor& floor, float particleDiameter);

/// A kill volume: granules whose centre enters this axis-aligned box are removed and counted.
struct Sink {
  Vec3 min{};
  Vec3 max{};
};

}  // namespace sandphys
