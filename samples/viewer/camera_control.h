#pragma once

#include <Eigen/Core>
#include <optional>

#include "app/sand_tools.h"
#include "render/camera.h"

namespace sandphys::viewer {

using samples::hitHorizontalPlane;
using samples::Ray;

/// How the mouse moves the renderer's orbit camera. Drags are in window pixels (the unit of GLFW
/// cursor positions), not framebuffer pixels, so that high-DPI screens feel the same.
namespace camera_control {

/// Elevation limit, rad: just short of the poles, where yaw would spin the view.
inline constexpr float kMaxPitch = 1.55f;
/// Distance limits, m.
inline constexpr float kMinDistance = 0.01f;
inline constexpr float kMaxDistance = 1.0e4f;

/// Turns the camera about its target by a drag of (dx, dy) pixels.
void orbit(render::Camera& camera, float dx, float dy);
/// Moves the target so that the scene follows a drag of (dx, dy) pixels in a window
/// `windowHeight` pixels high (the point under the cursor at the target's depth stays under it).
void pan(render::Camera& camera, float dx, float dy, float windowHeight);
/// Moves towards the target by `steps` wheel notches (negative: away).
void zoom(render::Camera& camera, float steps);
/// The ray from the eye through window point (x, y), pixels from the top left, of a window of
/// `width` × `height` pixels.
Ray rayThrough(const render::Camera& camera, float x, float y, float width, float height);

}  // namespace camera_control

}  // namespace sandphys::viewer
