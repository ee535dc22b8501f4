#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// A block of `counts` granules at `spacing` (m) centred on the y axis, its lowest lattice
/// centres `lift` (m) above y = 0: the bed or berm a scene's body acts on once it has settled.
GranuleBlock blockAbove(float lift, const Count3& counts, float spacing, std::uint64_t seed);

/// The body `id` in a read-back, or nullptr when it is not there (or `id` is invalid).
const BodyState* find(std::span<const BodyState> bodies, BodyId id);

/// The sand's force on the body `id` since the last call (World::takeBodyForces, a sync point,
/// which restarts every body's sums), or nothing when the World reports none for it.
std::optional<BodyForce> takeForceOn(World& world, BodyId id);

/// `state` as the metrics report it, its tilt the angle between world y and `up` (the body's up
/// axis at the start, in its own frame) turned by its orientation now, degrees.
SceneBody sceneBody(std::string name, const BodyState& state, Vec3 up = {0.0f, 1.0f, 0.0f});

}  // namespace sandphys::scenes::kit
