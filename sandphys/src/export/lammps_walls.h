#pragma once

// The deck's walls: each collider as a region and a granular wall on the clumps (lammps_deck.cpp).

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "export/lammps_scene.h"
#include "sandphys/colliders.h"
#include "sandphys/contact_model.h"

namespace sandphys::detail {

/// The deck's lines for `colliders`: the variables their regions name, then a region and a fix
/// wall/gran/region on the clumps per collider, with sandphys's rigid-wall stiffnesses and each
/// collider's friction and restitution. What differs from sandphys goes into `notes`.
struct LammpsWalls {
  std::string variables;
  std::string walls;
};
/// With rolling friction μ_r > 0, each wall's contact has its rolling model (lammpsRolling) at
/// overlap `rollingOverlap`.
LammpsWalls lammpsWalls(const std::vector<ColliderShape>& colliders, const ContactModel& model,
                        const LammpsScene& scene, double rollingFriction, double rollingOverlap,
                        std::vector<std::string>& notes);

}  // namespace sandphys::detail
