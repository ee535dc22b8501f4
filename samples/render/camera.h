#pragma once

#include <Eigen/Core>
#include <optional>

#include "scenes/scene.h"

namespace sandphys::render {

/// An orbit camera: it looks at `target` from `distance` away, turned by `yaw` about the y axis
/// and raised by `pitch` above the horizontal. Right-handed, y up, OpenGL clip conventions.
struct Camera {
  /// Point looked at, m (world).
  Eigen::Vector3f target{0.0f, 0.0f, 0.0f};
  /// Eye to target, m; > 0.
  float distance = 5.0f;
  /// Rotation of the eye about the target's vertical, rad; 0 puts the eye on +z.
  float yaw = 0.6f;
  /// Elevation of the eye, rad; in (-π/2, π/2).
  float pitch = 0.45f;
  /// Vertical field of view, rad; in (0, π).
  float fovY = 0.75f;
  /// What the camera was framed on (framing sets it; orbiting keeps it): colliders between the
  /// eye and this box are drawn see-through, so that a wall never hides the sand.
  std::optional<scenes::SceneBounds> focus;

  /// Eye position, m (world).
  Eigen::Vector3f eye() const;
  /// World to view (the eye looks down -z).
  Eigen::Matrix4f view() const;
  /// View to clip for a viewport of width / height `aspect`; near and far planes follow the
  /// distance (1/100 and 100 times it), which keeps depth precise around the target.
  Eigen::Matrix4f projection(float aspect) const;

  /// A camera that looks at `view.focus` from the view's direction and fits its eight corners
  /// into a viewport of the given aspect ratio (width / height), leaving out its left
  /// `coveredLeft` fraction (a panel drawn over it): the focus sits in the middle of the rest.
  static Camera framing(const scenes::SceneView& view, float aspect = 16.0f / 9.0f,
                        float coveredLeft = 0.0f);
};

/// Right-handed look-at view matrix.
Eigen::Matrix4f lookAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                       const Eigen::Vector3f& up);
/// OpenGL orthographic projection (clip z in [-1, 1]).
Eigen::Matrix4f orthographic(float left, float right, float bottom, float top, float near,
                             float far);
/// OpenGL perspective projection (clip z in [-1, 1]); fovY in rad.
Eigen::Matrix4f perspective(float fovY, float aspect, float near, float far);

}  // namespace sandphys::render
