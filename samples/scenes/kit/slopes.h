#pragma once

#include <span>

#include <sandphys/sandphys.h>

#include "scenes/kit/geometry.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// Whether `point` is inside `bounds`, faces included.
bool inBounds(const SceneBounds& bounds, const Vec3& point);

/// A box collider of `material` that holds the sand inside `bounds`.
Box containerBox(const SceneBounds& bounds, const SurfaceMaterial& material = {});

/// Mean displacement (m) along the unit vector `direction` of the alive granules of `bodies` from
/// where they were in `reference`; 0 when none was there.
double meanDisplacement(const Reference& reference, std::span<const BodyState> bodies,
                        const Vec3& direction);

}  // namespace sandphys::scenes::kit
